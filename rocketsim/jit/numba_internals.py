"""Every use of numba's private API, in one module, checked against the numba it was written for.

numba's public API compiles a function and caches it; what rocketsim's kernels
need beyond that reaches into numba's internals, here and nowhere else:

1. **Own callees** (:func:`_own_callees`): each kernel's machine code keeps its
   own copies of the kernels it calls. Touches ``numba.core.codegen.CPUCodeLibrary``'s
   ``_optimize_final_module`` and ``_final_module``, and llvmlite's linkage of a
   function.
2. **Optimisation level**: ``numba.core.config.OPT`` set to
   :data:`~rocketsim.jit.settings.OPT_LEVEL` (type ``_OptLevel``) unless
   ``NUMBA_OPT`` is set.
3. **Cache folder**: ``numba.config.CACHE_DIR`` set to
   :func:`rocketsim.jit.cache.cache_dir`.
4. **Plain call templates** (:func:`_call_template`): a constant argument typed as
   its kind, one signature for every constant. Replaces a dispatcher's
   ``get_call_template``.
5. **Compiled once among processes** (:func:`_compile_once`): wraps a dispatcher's
   ``compile`` and reads its ``overloads``, ``numba.core.sigutils.normalize_signature``,
   ``numba.core.compiler_lock.global_compiler_lock`` and the target's
   ``codegen().magic_tuple()``.
6. **Locked saves** (:func:`_save_locked`): wraps the dispatcher's cache's
   ``save_overload`` (``Dispatcher._cache``).
7. **The cache's index** (:func:`cached`, :func:`cached_signatures`): the cache's
   ``_index_key`` and ``_cache_file._load_index``.
8. **Types and entries** (:func:`numba_types`, :func:`entry`): a dispatcher's
   ``typeof_pyval``, the entry point its ``compile`` returns, and the ``_numba_type_``
   attribute by which numba's ``typeof`` types a :class:`~rocketsim.jit.kernel.Kernel`
   as its dispatcher.
9. **Damaged files read as missing** (:func:`_healed`): wraps the dispatcher's
   cache file's (``_cache._cache_file``) ``_load_index`` and ``load``.
10. **Intrinsics** (:func:`is_intrinsic`): ``numba.core.extending._Intrinsic``, the
   class of machine code written with ``@intrinsic``, which has no Python form.
11. **Signatures pickled** (:func:`serialized`): ``numba.core.serialize.dumps``, numba's
   own pickler (its cache's), which pickles a type holding a class made at run time
   (a C function pointer's typing template) by value; ``pickle`` reads it back.

:func:`check` finds each of these as :data:`TESTED` numba has them and raises
:class:`NumbaChanged`, naming the numba installed and what it lacks, when one is
missing or changed: a numba release that moved an internal fails the first
compile loudly instead of compiling slower kernels in silence. Each patch's
effect is tested (tests/unit/jit/test_jit_numba_internals.py), and pyproject.toml pins
numba to the :data:`TESTED` releases; a numba outside them warns once
(:class:`UntestedNumba`).

Why own callees: numba links a copy of every callee into each kernel's module as
a weak definition (``linkonce_odr``), and the JIT's linker binds a weak symbol to
the first definition it loaded: a kernel loaded after another that holds the same
callees (the telemetry sample's kernel carries the derivative, as the compiled
runs do) called them in that other kernel's code, through a stub each call, and
ran slower than loaded first. Internal, each kernel's calls stay in its
own code, whatever the order of loading; the machine code is otherwise the same,
the results the same bits. It applies to every function numba compiles in the
process once rocketsim has loaded numba (a notebook's own ``numba.njit``
functions included), with the same effect on them.

Why damaged files are read as missing: numba reads a kernel's index and data
files with ``pickle`` and lets any error of a file cut short (a full disk, a
killed process, a copy interrupted) or overwritten propagate, so every later
flight failed with a traceback until the folder was deleted by hand. A file
that cannot be read is taken as absent, with one line on stderr naming it: the
kernel is compiled again and its files written anew (a damaged index loses the
kernel's other signatures, compiled again when next needed).

Why the optimisation level: numba optimises each kernel's module again with every
kernel it calls linked in, so the big kernels' compiling is mostly LLVM's; at
level 1 (numba's default is 3) the flights compile faster and run as fast. Without
``fastmath`` no level may reorder or fuse floating-point operations: the
telemetry is the same to the byte at either level.
"""

from __future__ import annotations

import functools
import inspect
import os
import warnings

from rocketsim.jit import cache
from rocketsim.jit.settings import current

TESTED = ("0.68",)      # numba's releases (major.minor) this module was written and tested against


class NumbaChanged(RuntimeError):
    """The installed numba lacks, or has changed, an internal rocketsim patches."""


class UntestedNumba(UserWarning):
    """The installed numba is not one of the :data:`TESTED` releases."""


def _numba_version() -> str:
    import numba
    return numba.__version__


def tested(version: str) -> bool:
    """Whether numba ``version`` (``"0.68.1"``) is one of the :data:`TESTED` releases."""
    return ".".join(version.split(".")[:2]) in TESTED


def _changed(what: str) -> NumbaChanged:
    return NumbaChanged(
        f"numba {_numba_version()} is not the numba rocketsim's kernels were written for: {what}. "
        f"rocketsim patches numba's internals as numba {' / '.join(TESTED)} has them; install a "
        f"tested numba (pip install 'numba>={TESTED[0]},<{_next(TESTED[-1])}').")


def _next(release: str) -> str:
    major, minor = release.split(".")
    return f"{major}.{int(minor) + 1}"


def _method(owner, name: str, parameters: tuple[str, ...]) -> None:
    """Raise :class:`NumbaChanged` unless ``owner.name`` is a function of ``parameters``."""
    found = inspect.getattr_static(owner, name, None)
    if isinstance(found, functools.partialmethod) and found.func is _own_callees:
        found = found.args[0]           # numba's, as patched by numba_njit
    if not callable(found):
        raise _changed(f"{owner.__module__}.{owner.__qualname__}.{name} is missing")
    have = tuple(inspect.signature(found).parameters)
    if have != parameters:
        raise _changed(f"{owner.__module__}.{owner.__qualname__}.{name} takes {have}, "
                       f"not {parameters}")


def check() -> None:
    """Raise :class:`NumbaChanged` if an internal this module uses is missing or changed
    (see the module); warn (:class:`UntestedNumba`) if numba is not a tested release."""
    from llvmlite import binding
    from numba.core import (caching, codegen, compiler_lock, config, errors, extending, registry, serialize,
                            sigutils, types)

    _method(codegen.CPUCodeLibrary, "_optimize_final_module", ("self",))
    _method(codegen.CPUCodegen, "magic_tuple", ("self",))
    if not hasattr(binding.Linkage, "linkonce_odr"):
        raise _changed("llvmlite.binding.Linkage has no linkonce_odr")
    if not hasattr(config, "OPT") or not hasattr(config, "CACHE_DIR"):
        raise _changed("numba.core.config has no OPT or no CACHE_DIR")
    _method(registry.CPUDispatcher, "get_call_template", ("self", "args", "kws"))
    _method(registry.CPUDispatcher, "compile", ("self", "sig"))
    _method(registry.CPUDispatcher, "typeof_pyval", ("self", "val"))
    _method(caching.FunctionCache, "save_overload", ("self", "sig", "data"))
    _method(caching.FunctionCache, "_index_key", ("self", "sig", "codegen"))
    _method(caching.IndexDataCacheFile, "_load_index", ("self",))
    _method(caching.IndexDataCacheFile, "load", ("self", "key"))
    for module, name in ((sigutils, "normalize_signature"), (compiler_lock, "global_compiler_lock"),
                         (types, "unliteral"), (errors, "TypingError"), (extending, "_Intrinsic"),
                         (serialize, "dumps")):
        if not hasattr(module, name):
            raise _changed(f"{module.__name__}.{name} is missing")
    if not tested(_numba_version()):
        warnings.warn(f"numba {_numba_version()} is not a release rocketsim was tested with "
                      f"({' / '.join(TESTED)}); its kernels may compile or run differently",
                      UntestedNumba, stacklevel=2)


@functools.cache
def numba_njit():
    """numba's ``njit``, numba imported and checked (:func:`check`), pointed at the cache
    folder, set to the kernels' optimisation level and keeping each kernel's callees its own
    (once)."""
    import numba
    from numba.core import codegen, config

    check()
    settings = current()
    numba.config.CACHE_DIR = cache.cache_dir()
    if not settings.opt_from_numba:
        config.OPT = type(config.OPT)(int(settings.opt_level))
    library = codegen.CPUCodeLibrary
    library._optimize_final_module = functools.partialmethod(_own_callees, library._optimize_final_module)
    return numba.njit


def _own_callees(library, optimize) -> None:
    """numba's optimising of a kernel's machine code (``optimize``), after the functions its
    module holds for the kernels it calls are made internal to it (see the module)."""
    from llvmlite import binding

    module = getattr(library, "_final_module", None)
    if module is None:
        raise _changed("a code library being optimised has no _final_module")
    for function in module.functions:
        if not function.is_declaration and function.linkage == binding.Linkage.linkonce_odr:
            function.linkage = "internal"
    optimize(library)


def dispatcher(func, options: dict):
    """numba's dispatcher of ``func`` compiled with ``options``, made to type constant
    arguments plainly, to compile each signature once among the processes sharing the
    cache, and to save under the cache's lock."""
    made = numba_njit()(**options)(func)
    made.get_call_template = functools.partial(_call_template, made)
    made.compile = functools.partial(_compile_once, made.compile, made)
    saved = getattr(made, "_cache", None)
    if saved is not None and options.get("cache"):
        if not hasattr(saved, "save_overload"):
            raise _changed("a caching dispatcher's _cache has no save_overload")
        saved.save_overload = functools.partial(_save_locked, saved.save_overload)
        files = getattr(saved, "_cache_file", None)
        if files is None or not hasattr(files, "_load_index") or not hasattr(files, "load"):
            raise _changed("a caching dispatcher's _cache._cache_file has no _load_index or load")
        files._load_index = functools.partial(_healed, files._load_index, files._index_path, {})
        files.load = functools.partial(_healed_load, files.load, files)
    return made


_DAMAGED: set[str] = set()      # the damaged cache files found (the first said on stderr)


def _healed(read, path: str, missing, *args):
    """``read(*args)`` of a kernel's cache file at ``path``, or ``missing`` (what numba reads
    for an absent file) when the file cannot be read, said in one line on stderr."""
    try:
        return read(*args)
    except Exception as error:          # noqa: BLE001 - any error of unpickling a damaged file
        import sys
        if not _DAMAGED:
            print(f"rocketsim: the kernel cache file {path} is damaged ({type(error).__name__}: "
                  f"{str(error)[:80]}); it and any other damaged one are compiled again",
                  file=sys.stderr)
        _DAMAGED.add(path)
        return missing


def _healed_load(load, files, key):
    """numba's ``load`` of the data file of ``key`` in the cache file ``files``, None (not
    cached: compiled again and saved over it) when that file cannot be read."""
    name = files._load_index().get(key)
    path = os.path.join(files._cache_path, name) if name else files._index_path
    return _healed(load, path, None, key)


def _call_template(dispatcher, args, kws):
    """numba's ``get_call_template`` of ``dispatcher`` (how a kernel calling it types the
    call) for the arguments' plain types: a constant argument (``orbit_into(out, 17, ...)``,
    ``_rotation(2, angle)``) is typed as its kind (int64), not as the literal value, so
    that one compiled signature serves every constant (numba compiled one per value).
    A kernel that can only be typed with the literal (a branch on it that types only
    when pruned) keeps it. Values and floating-point operations are the same either way.
    """
    from numba.core import errors, types

    plain = tuple(types.unliteral(a) for a in args)
    plain_kws = {k: types.unliteral(v) for k, v in kws.items()}
    if plain != tuple(args) or plain_kws != kws:
        try:
            return type(dispatcher).get_call_template(dispatcher, plain, plain_kws)
        except errors.TypingError:
            pass
    return type(dispatcher).get_call_template(dispatcher, args, kws)


def _compile_once(compile, dispatcher, sig):
    """numba's ``compile`` of ``dispatcher`` for ``sig`` (its loading from the cache, else its
    compiling), once among the processes that share the cache.

    Before compiling a signature it has not loaded, a process takes a marker for it
    (:func:`rocketsim.jit.cache.take`: kernel, argument types and the machine code's
    target) and releases it once the compiled signature is saved; a process that finds
    another's marker waits for it and then loads the signature from the cache. The
    markers are taken under numba's compiler lock, so the threads of one process never
    wait for each other's; the kernels call no kernel that calls them back, so no two
    processes wait for each other's."""
    from numba.core import sigutils
    from numba.core.compiler_lock import global_compiler_lock

    with global_compiler_lock:
        args = tuple(sigutils.normalize_signature(sig)[0])
        marker = None
        if args not in dispatcher.overloads:
            func = dispatcher.py_func
            what = f"{func.__module__}.{func.__qualname__}{args}{dispatcher.targetctx.codegen().magic_tuple()}"
            marker = cache.marker(_cache_folder(), what)
        taken = marker is not None and cache.take(marker)
        try:
            return compile(sig)
        finally:
            if taken:
                cache.release(marker)


def _cache_folder() -> str:
    """The folder numba caches the kernels in (set by :func:`numba_njit`)."""
    import numba
    return numba.config.CACHE_DIR


def _save_locked(save, sig, data) -> None:
    """numba's ``save_overload`` of a kernel's cache, holding the cache folder's lock
    (:func:`rocketsim.jit.cache.locked`).

    numba saves a compiled signature by reading the kernel's index, picking the next
    free data file's number, writing the index, then the data: two processes saving
    two signatures of one kernel at once can both pick the same number, and the index
    then names the other signature's machine code, which every later process loads and
    runs (numba issues 4807, 10128). Under the lock the index read, the number and both
    writes are one step; numba writes each file to a temporary name and renames it, so a
    process loading meanwhile reads an index and data that belong together.

    A cache folder that cannot be written (read-only, a full disk, no permission) is
    said once on stderr and the kernel kept in memory, for this process: the flight
    flies with the kernels it could load and those it compiled."""
    try:
        with cache.locked(_cache_folder()):
            save(sig, data)
    except OSError as error:
        if not _UNWRITABLE:
            import sys
            print(f"rocketsim: the kernel cache folder {_cache_folder()} cannot be written "
                  f"({error.strerror or error}); kernels not in it are compiled for this process "
                  "only", file=sys.stderr)
        _UNWRITABLE.append(error)


_UNWRITABLE: list[OSError] = []     # the errors of saves into a cache folder that cannot be written


def numba_types(kernel, args) -> tuple:
    """The numba types of the values ``args`` as ``kernel`` would type them when called."""
    typeof = kernel.dispatcher.typeof_pyval
    return tuple(typeof(a) for a in args)


def entry(kernel, signature: tuple):
    """``kernel``'s compiled entry for the numba types ``signature`` (compiled, or loaded from
    the cache, on first need): a function of arguments of those types that skips the
    dispatcher's typing of them."""
    return kernel.dispatcher.compile(signature)


def cached(kernel, signature: tuple) -> bool:
    """Whether ``kernel`` is compiled for the numba types ``signature`` in this process or in
    the cache (its index names the signature for this machine)."""
    found = kernel.dispatcher
    if signature in found.overloads:
        return True
    saved = found._cache
    if getattr(saved, "_cache_file", None) is None:         # compiled uncached
        return False
    return saved._index_key(signature, found.targetctx.codegen()) in saved._cache_file._load_index()


def cached_signatures(kernel) -> list[tuple]:
    """The argument types of every signature of ``kernel`` in the cache's index."""
    saved = getattr(kernel.dispatcher, "_cache", None)
    index = getattr(saved, "_cache_file", None)
    return [key[0] for key in index._load_index()] if index is not None else []


def serialized(value) -> bytes:
    """``value`` pickled by numba's own pickler (numba types included; ``pickle.loads``
    reads it)."""
    from numba.core import serialize
    return serialize.dumps(value)


def is_intrinsic(value) -> bool:
    """Whether ``value`` is a numba intrinsic (machine code with no Python form); False
    while numba is not loaded (nothing can be one)."""
    import sys

    extending = sys.modules.get("numba.core.extending")
    return extending is not None and isinstance(value, extending._Intrinsic)


def applied(kernel=None) -> dict[str, bool]:
    """Which patches are in place: the process's (once a kernel's dispatcher is made) and,
    given a :class:`~rocketsim.jit.kernel.Kernel`, its dispatcher's."""
    import numba
    from numba.core import codegen, config

    def wraps(method, patch) -> bool:
        return getattr(method, "func", None) is patch

    optimize = codegen.CPUCodeLibrary.__dict__.get("_optimize_final_module")
    settings = current()
    found = {
        "own callees": isinstance(optimize, functools.partialmethod) and optimize.func is _own_callees,
        "optimisation level": settings.opt_from_numba or int(config.OPT) == int(settings.opt_level),
        "cache folder": numba.config.CACHE_DIR == cache.cache_dir(),
    }
    if kernel is not None:
        made = kernel.dispatcher
        found["plain call templates"] = wraps(made.get_call_template, _call_template)
        found["compiled once"] = wraps(made.compile, _compile_once)
        found["locked saves"] = wraps(made._cache.save_overload, _save_locked)
        found["damaged files read as missing"] = wraps(made._cache._cache_file.load, _healed_load)
    return found
