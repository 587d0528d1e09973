"""The one way the library compiles kernels.

`njit` is numba's ``njit`` with the project's settings: compiled kernels are
cached on disk (``cache=True``) so a second ``rocketsim fly`` starts flying
without recompiling, ``fastmath`` stays off so results are IEEE-exact and
bit-identical run to run, and division by zero follows numpy (inf/nan) rather
than raising inside the hot path. The compiled runs of many steps and the
telemetry's framing are compiled ``nogil=True``: while they run, the
telemetry's writing thread (:mod:`rocketsim.telemetry.writing_thread`) runs
its Python beside them. The calls of one or a few steps at a time keep the
GIL: released and taken again every step, it would hand it to the writing
thread and back tens of times a batch of samples, each hand-over a
thread's wake-up.

A kernel that makes no array and returns none (the derivative and the forces
it sums: they read their arguments and return numbers) is compiled
``njit(borrows=True)``: without numba's reference counting (NRT), so it borrows
its caller's arrays. numba otherwise counts a reference to every array of every
argument a kernel binds, with an atomic increment and decrement each: a staged
vehicle's arrays are a named tuple of some 35, passed down through the
derivative's calls four times a step, and those counts were a third of an RK4
step's time (3.3 us -> 2.2 us for the sounding rocket of the peer benchmark).
numba refuses to compile such a kernel if it makes an array; one that returned
an array (a view, or its argument) would hand its caller a reference it never
counted, so a test checks every borrowing kernel's compiled return types. Every
other kernel counts its references (``_nrt`` set, not inherited from a borrowing
caller), so which callees count does not depend on the order of compiling.

Each kernel's machine code holds its own copies of the kernels it calls,
internal to it (:func:`_own_callees`): numba links them in as weak symbols,
which the JIT's linker would bind to the first copy loaded, in another kernel's
code, through a stub per call.

LLVM optimises the kernels at level 1 (:data:`OPT_LEVEL`; numba's default is 3)
unless ``NUMBA_OPT`` says otherwise: numba optimises each kernel's module again
with every kernel it calls linked in, so the big kernels' compiling is mostly
LLVM's, and at level 1 a cold Falcon 9 mission compiles in about 8 % less CPU
time while the flights run as fast (within the benchmarks' noise). Without
``fastmath`` no level may reorder or fuse floating-point operations: the
telemetry is the same to the byte at either level.

numba itself (about half a second to import, more with the scipy it pulls in)
is imported only when a kernel is first called or compiled: ``njit`` returns a
:class:`Kernel`, which makes numba's dispatcher on first need. A command that
only reads files (``rocketsim validate``, ``schema``, ``replay`` of a summary)
imports the kernel modules for their constants and never loads numba. Another
kernel refers to a :class:`Kernel` as to the dispatcher itself (numba types it
through ``_numba_type_``), so kernels compile and inline exactly as before.

numba's cache checks only the source file of the function it compiled, not
the functions that function calls from other modules: after an edit to
``bodies/gravity.py`` a cached ``dynamics/derivative.py`` kernel would still
run the old gravity. So the cache lives in a folder named for a hash of the
source of every module that compiles a kernel and of every library module
those import, followed to closure, and of numba's version and the optimisation
level (``~/.cache/rocketsim/numba-<hash>``, or
below ``$ROCKETSIM_CACHE_DIR``): a change to any module a kernel could read
(its functions or its module-level constants) starts a fresh cache, while
an edit to the pure-Python layers (the simulation loop, the flight computer,
scenarios, telemetry) keeps the compiled kernels. Hashing costs a few
milliseconds at import.
"""

import functools
import hashlib
import os
import re
from pathlib import Path

import numpy as np

_OPTIONS = {"cache": True, "fastmath": False, "error_model": "numpy", "_nrt": True}
OPT_LEVEL = 1       # LLVM's optimisation level of the kernels, unless NUMBA_OPT is set (see the module)


# "from rocketsim.a import b, c", a parenthesised list over several lines, or "import rocketsim.a"
_IMPORT = re.compile(r"^\s*(?:from\s+(rocketsim(?:\.\w+)*)\s+import\s+(\([^)]*\)|[\w ,]+)"
                     r"|import\s+(rocketsim(?:\.\w+)*))", re.M)


def _kernel_sources(package: Path) -> list[Path]:
    """The modules that compile kernels and every library module they import, transitively."""
    paths = {}
    for path in package.rglob("*.py"):
        name = path.relative_to(package).with_suffix("").as_posix().replace("/", ".")
        paths[name.removesuffix("__init__").rstrip(".")] = path
    texts = {name: path.read_text() for name, path in paths.items()}

    def imported(text: str) -> set[str]:
        found = set()
        for match in _IMPORT.finditer(text):
            module = (match.group(1) or match.group(3)).removeprefix("rocketsim").lstrip(".")
            names = re.split(r"[\s,()]+", match.group(2) or "")
            found |= {candidate for candidate in [module] + [f"{module}.{n}".lstrip(".") for n in names if n]
                      if candidate in texts}
        return found

    todo = [name for name, text in texts.items() if "njit" in text]
    closure = set(todo)
    while todo:
        for name in imported(texts[todo.pop()]) - closure:
            closure.add(name)
            todo.append(name)
    return sorted(paths[name] for name in closure)


def _source_hash() -> str:
    from importlib.metadata import version
    digest = hashlib.sha256(f"{version('numba')} opt {_opt_level()}".encode())
    package = Path(__file__).resolve().parent
    for path in _kernel_sources(package):
        digest.update(path.relative_to(package).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def cache_dir() -> str:
    """The folder of this source's compiled kernels: ``$NUMBA_CACHE_DIR`` if set, else
    ``numba-<hash>`` below ``$ROCKETSIM_CACHE_DIR`` (default ``~/.cache/rocketsim``)."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return os.environ["NUMBA_CACHE_DIR"]
    root = os.environ.get("ROCKETSIM_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"), "rocketsim")
    return os.path.join(root, f"numba-{_source_hash()}")


def _opt_level() -> str:
    """The kernels' LLVM optimisation level: ``$NUMBA_OPT`` if set, else :data:`OPT_LEVEL`."""
    return os.environ.get("NUMBA_OPT") or str(OPT_LEVEL)


@functools.cache
def _numba_njit():
    """numba's ``njit``, numba imported, pointed at :func:`cache_dir`, set to
    :func:`_opt_level` and keeping each kernel's callees its own (:func:`_own_callees`)
    (once)."""
    import numba
    from numba.core import codegen, config
    numba.config.CACHE_DIR = cache_dir()
    if not os.environ.get("NUMBA_OPT"):
        config.OPT = type(config.OPT)(OPT_LEVEL)
    library = codegen.CPUCodeLibrary
    library._optimize_final_module = functools.partialmethod(_own_callees, library._optimize_final_module)
    return numba.njit


def _own_callees(library, optimize) -> None:
    """numba's optimising of a kernel's machine code (``optimize``), after the functions its
    module holds for the kernels it calls are made internal to it.

    numba links a copy of every callee into each kernel's module as a weak definition
    (``linkonce_odr``), and the JIT's linker binds a weak symbol to the first definition
    it loaded: a kernel loaded after another that holds the same callees (the telemetry
    sample's kernel carries the derivative, as the compiled runs do) called them in that
    other kernel's code, through a stub each call, and ran 15-35 % slower than loaded
    first (the F9 mission's runs 831 against 688 ms). Internal, each kernel's calls stay
    in its own code, whatever the order of loading; the machine code is otherwise the
    same, the results the same bits. It applies to every function numba compiles in the
    process once rocketsim has loaded numba (a notebook's own ``numba.njit`` functions
    included), with the same effect on them."""
    from llvmlite import binding

    for function in library._final_module.functions:
        if not function.is_declaration and function.linkage == binding.Linkage.linkonce_odr:
            function.linkage = "internal"
    optimize(library)


def _save_locked(save, sig, data) -> None:
    """numba's ``save_overload`` of a kernel's cache, holding an exclusive lock on the
    cache folder's ``.lock`` file (POSIX ``flock``; unlocked where there is none).

    numba saves a compiled signature by reading the kernel's index, picking the next
    free data file's number, writing the index, then the data: two processes saving
    two signatures of one kernel at once (two test workers, two campaign workers, the
    parallel ``rocketsim compile``) can both pick the same number, and the index then
    names the other signature's machine code, which every later process loads and runs
    (numba issues 4807, 10128). Under the lock the index read, the number and both writes are one
    step; numba writes each file to a temporary name and renames it, so a process
    loading meanwhile reads an index and data that belong together."""
    try:
        import fcntl
    except ImportError:                 # no flock (Windows): numba's own behaviour
        save(sig, data)
        return
    import numba
    folder = numba.config.CACHE_DIR     # this source's folder (set by _numba_njit)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, ".lock"), "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            save(sig, data)
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


def _compile_once(compile, dispatcher, sig):
    """numba's ``compile`` of ``dispatcher`` for ``sig`` (its loading from the cache, else its
    compiling), once among the processes that share the cache.

    Before compiling a signature it has not loaded, a process creates a marker file for it
    (below the cache folder's ``.compiling``: kernel, argument types and the machine code's
    target; its host and process number in it) and removes it once the compiled signature is
    saved. A process that finds the marker of another living process waits for it to go and
    then loads the signature from the cache: two processes on a cold cache (the compiling
    process beside a flight, the test workers, a campaign's workers, ``rocketsim compile``'s
    pool) compile each kernel once between them, nested callees included. A marker whose
    process has ended is taken over; a wait is at most :data:`COMPILE_WAIT` s. The markers
    are taken under numba's compiler lock, so the threads of one process never wait for each
    other's; the kernels call no kernel that calls them back, so no two processes wait for
    each other's."""
    from numba.core import sigutils
    from numba.core.compiler_lock import global_compiler_lock

    with global_compiler_lock:
        args = tuple(sigutils.normalize_signature(sig)[0])
        marker = None if args in dispatcher.overloads else _marker(dispatcher, args)
        taken = marker is not None and _take(marker)
        try:
            return compile(sig)
        finally:
            if taken:
                try:
                    os.remove(marker)
                except OSError:
                    pass


COMPILE_WAIT = 120.0        # s: the longest a process waits for another's compiling of a kernel


def _marker(dispatcher, args: tuple) -> str | None:
    """The marker file of ``dispatcher``'s signature ``args`` (see :func:`_compile_once`),
    its folder made; None where it cannot be."""
    import numba

    func = dispatcher.py_func
    what = f"{func.__module__}.{func.__qualname__}{args}{dispatcher.targetctx.codegen().magic_tuple()}"
    folder = os.path.join(numba.config.CACHE_DIR, ".compiling")
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError:
        return None
    return os.path.join(folder, hashlib.sha256(what.encode()).hexdigest()[:32])


def _take(marker: str) -> bool:
    """Create ``marker`` for this process, first waiting while another living process holds
    it; False (compile without it) when it cannot be made or the wait ran out."""
    import socket
    import time

    me = f"{socket.gethostname()} {os.getpid()}".encode()
    deadline = time.monotonic() + COMPILE_WAIT
    while True:
        try:
            handle = os.open(marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
        except FileExistsError:
            pass
        except OSError:
            return False
        else:
            os.write(handle, me)
            os.close(handle)
            return True
        if time.monotonic() > deadline:
            return False
        if not _held(marker, me.split()[0].decode()):
            try:
                os.remove(marker)       # its process ended: taken over
            except OSError:
                pass
            continue
        time.sleep(0.005)


def _held(marker: str, host: str) -> bool:
    """Whether ``marker``'s process may still be compiling: a living process of this host,
    one of another host (which cannot be asked), or a marker being written."""
    try:
        with open(marker, "rb") as stream:
            owner = stream.read().split()
    except FileNotFoundError:
        return False
    except OSError:
        return True
    if len(owner) != 2 or owner[0].decode(errors="replace") != host:
        return True
    try:
        os.kill(int(owner[1]), 0)
    except ProcessLookupError:
        return False
    except (OSError, ValueError):
        return True
    return True


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


class Kernel:
    """A function compiled by numba on first need (see the module).

    Calling it calls the compiled function; every other attribute (``compile``,
    ``signatures``, ``typeof_pyval``...) is numba's dispatcher's.
    """

    def __init__(self, func, options: dict):
        functools.update_wrapper(self, func)
        self.py_func = func
        self._options = options
        self._dispatcher = None

    @property
    def dispatcher(self):
        """numba's dispatcher of this kernel (made, and numba imported, on first use)."""
        if self._dispatcher is None:
            dispatcher = _numba_njit()(**self._options)(self.py_func)
            dispatcher.get_call_template = functools.partial(_call_template, dispatcher)
            dispatcher.compile = functools.partial(_compile_once, dispatcher.compile, dispatcher)
            cache = getattr(dispatcher, "_cache", None)
            if cache is not None and hasattr(cache, "save_overload"):
                cache.save_overload = functools.partial(_save_locked, cache.save_overload)
            self._dispatcher = dispatcher
        return self._dispatcher

    @property
    def _numba_type_(self):
        return self.dispatcher._numba_type_

    def __call__(self, *args):
        if self in BESIDE.kernels:          # queued for the second process: see CompiledBeside
            BESIDE.wait_for(self, tuple(self.typeof_pyval(a) for a in args))
        return self.dispatcher(*args)

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.dispatcher, name)

    def __repr__(self) -> str:
        return f"<kernel {self.__module__}.{self.__qualname__}>"


def njit(func=None, **options):
    """Compile ``func`` on first need (use as ``@njit`` or ``@njit(inline="always")``);
    ``borrows=True``: without reference counting (see the module)."""
    settings = {**_OPTIONS, **options}
    if settings.pop("borrows", False):
        settings["_nrt"] = False
    if func is None:
        return functools.partial(Kernel, options=settings)
    return Kernel(func, settings)


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def copy_into(dst, start, src):
    """Write the 1-D array ``src`` into ``dst[start:start + len(src)]``, element by element.

    What ``dst[start:stop] = src`` does, without its compiled check of the two shapes: that
    check formats numba's error message ("cannot assign slice of shape ..."), whose string
    code takes 2-3 s to compile in each process that first needs it, on a cold cache."""
    for i in range(src.shape[0]):
        dst[start + i] = src[i]


def entry_point(kernel, *args):
    """The compiled entry of ``kernel`` for the numba types of ``args`` (compiled, or
    loaded from the cache, on first need), to call with arguments of those same types.

    Calling a kernel through numba's dispatcher types every argument on every
    call; for a named tuple of arrays (a staged vehicle's ``VehicleArrays``)
    that costs about 8 us, more than a derivative. A caller that calls a kernel
    every step with the same objects binds the entry once and calls it directly.
    Entries are kept by the arguments' kinds (:func:`_kinds`), so a second world
    of the same shapes binds its entries without numba typing its arguments again
    (some 0.5 ms for a staged vehicle's arrays).
    """
    kinds = _kinds(args)
    entry = _ENTRIES.get((kernel, kinds)) if kinds is not None else None
    if entry is None:
        signature = tuple(kernel.typeof_pyval(a) for a in args)
        if kernel in BESIDE.kernels:
            BESIDE.wait_for(kernel, signature)
        entry = kernel.compile(signature)
        if kinds is not None:
            _ENTRIES[kernel, kinds] = entry
    return entry


_ENTRIES: dict = {}     # (kernel, the arguments' kinds) -> compiled entry (entry_point)


def _kinds(values) -> tuple | None:
    """Everything numba's type of each of ``values`` depends on, for the values this
    library passes: an array's dtype, dimensions, layout, writeability and alignment;
    a (named) tuple's class and its items' kinds; a numpy scalar's dtype (a
    datetime's unit is in it); a number's, bytes', text's or None's class (an
    integer's, and whether it fits int64). None where a value is of another sort,
    to be typed by numba."""
    kinds = []
    for value in values:
        cls = type(value)
        if cls is np.ndarray:
            flags = value.flags
            kinds.append((value.dtype, value.ndim, flags.c_contiguous, flags.f_contiguous,
                          flags.writeable, flags.aligned))
        elif cls is int:
            kinds.append((cls, -2**63 <= value < 2**63))
        elif isinstance(value, np.generic):
            kinds.append(value.dtype)
        elif cls in (float, bool, bytes, str, type(None)):
            kinds.append(cls)
        elif isinstance(value, tuple):
            items = _kinds(value)
            if items is None:
                return None
            kinds.append((cls, items))
        else:
            return None
    return tuple(kinds)


class Entries:
    """Compiled entries bound to one owner's arguments (see :func:`entry_point`).

    ``call(kernel, key, *args)`` returns ``kernel(*args)``; the entry is bound on
    the first call and again whenever ``key`` (the argument whose type is
    costly to work out, e.g. a vehicle's arrays, replaced at staging) is a new
    object. The other arguments keep their kinds from call to call (numbers as
    numbers, float64 arrays, a type-level switch such as the step's ``nbody``
    None or not, as the owner's parameters say: a body keeps its n-body field
    from start to end, a handover re-centres it). An array that is not
    C-contiguous goes through the dispatcher instead.
    """

    def __init__(self):
        self._bound = {}

    def call(self, kernel, key, *args):
        for a in args:
            if type(a) is np.ndarray and not a.flags.c_contiguous:
                return kernel(*args)
        bound = self._bound.get(kernel)
        if bound is None or bound[0] is not key:
            bound = self._bound[kernel] = (key, entry_point(kernel, *args))
        return bound[1](*args)


BESIDE_IDLE = 2.0           # s: the second process ends after this long with nothing left to compile
# Whether a cold cache's kernels are queued for a second process; off where every core is
# compiling already (the pool of ``rocketsim compile``)
COMPILE_BESIDE = True


def cached(kernel, signature: tuple) -> bool:
    """Whether ``kernel`` is compiled for the numba types ``signature`` in this process or in
    the cache (its index names the signature for this machine). True where that cannot be
    told (a numba whose cache is laid out otherwise): nothing is then compiled beside."""
    dispatcher = kernel.dispatcher
    if signature in dispatcher.overloads:
        return True
    cache = getattr(dispatcher, "_cache", None)
    try:
        key = cache._index_key(signature, dispatcher.targetctx.codegen())
        return key in cache._cache_file._load_index()
    except Exception:       # noqa: BLE001 - numba's internals moved: do as if cached
        return True


def _claim(folder: str, name: str) -> bool:
    """Take the queued item ``name`` of ``folder`` for this process (False: taken already)."""
    try:
        os.close(os.open(os.path.join(folder, "claim-" + name), os.O_CREAT | os.O_EXCL | os.O_WRONLY))
    except OSError:         # it exists, or the folder is gone (the queue has ended)
        return False
    return True


def _take_item(folder: str, name: str) -> tuple | None:
    """The queued item ``name`` (kernel's module, name, signature), taken for this process;
    None where another has it or it is gone. Read before it is claimed: once claimed, the
    process that queued it may end and remove the folder, and the item is still compiled."""
    import pickle

    if os.path.exists(os.path.join(folder, "claim-" + name)):
        return None
    try:
        with open(os.path.join(folder, name), "rb") as stream:
            item = pickle.load(stream)
    except Exception:       # noqa: BLE001 - gone, or not whole: not taken
        return None
    return item if _claim(folder, name) else None


def _compile_item(folder: str, name: str, item: tuple) -> None:
    """Compile the queued ``item`` (:func:`_take_item`) and mark it done, whatever the
    outcome: a kernel that fails here fails again, with its message, where it is called."""
    import importlib

    module, qualname, signature = item
    try:
        getattr(importlib.import_module(module), qualname).compile(signature)
    except Exception:       # noqa: BLE001 - see the docstring
        pass
    finally:
        try:
            open(os.path.join(folder, "done-" + name), "wb").close()
        except OSError:
            pass


def _queued_items(folder: str) -> list[str]:
    """The queue's items, in the order they are compiled (by priority, then as queued)."""
    try:
        return sorted(name for name in os.listdir(folder) if name.startswith("item-"))
    except OSError:
        return []


def compile_queued(folder: str) -> None:
    """The second process of :class:`CompiledBeside`: compile the queue's items in order, each
    it claims before the first process does, until the queue has had nothing new for
    :data:`BESIDE_IDLE` seconds or its folder is gone."""
    import time

    tried: set[str] = set()
    idle_since = time.monotonic()
    while os.path.isdir(folder):
        for name in _queued_items(folder):
            if name not in tried:
                tried.add(name)
                item = _take_item(folder, name)
                if item is not None:
                    _compile_item(folder, name, item)
                idle_since = time.monotonic()
                break
        else:
            if time.monotonic() - idle_since > BESIDE_IDLE:
                return
            time.sleep(0.01)


class CompiledBeside:
    """Kernels of known argument types compiled into the cache by a second Python process
    while this one compiles others: on a cold cache the two cores compile at once (numba
    compiles one function at a time per process, under its compiler lock).

    :meth:`add` queues a kernel for the numba types of some arguments unless the cache
    has it; the second process starts with the first item and takes the items in order
    of priority (then as queued). When this process needs a queued kernel
    (:func:`entry_point`) it compiles it itself if the second process has not taken it,
    else waits for it there, meanwhile compiling the items not yet taken, and then loads it
    from the cache. The queue is a temporary folder: each item a file (the kernel's module,
    name and signature), taken by creating its ``claim-`` file (exclusive creation: one
    process wins), a ``done-`` file when compiled. The machine code is the same whichever
    process compiles it; a second process that fails or is slower than :data:`COMPILE_WAIT`
    costs the wait, and the kernel then compiles here as it would have. A kernel this process
    can fly without (a compiled run of many steps: one step at a time is the same flight) it
    does not wait for (:meth:`compiling_elsewhere`).
    """

    def __init__(self):
        self._folder: str | None = None
        self._process = None
        self._queued: dict[tuple, str] = {}    # (kernel, signature) -> its item's name, until needed here
        self._count = 0                         # items queued so far (their names' numbers)
        self._owner = None                      # the process that made the folder (not a forked child)
        self.kernels: set = set()               # the kernels of those items
        self._settled: set = set()              # (kernel, the arguments' kinds) found cached

    def add(self, kernel, args, priority: int = 0) -> bool:
        """Queue ``kernel`` for the numba types of ``args`` (lower ``priority`` first) unless
        it is cached, compiled here or queued; whether it was queued."""
        import pickle

        kinds = _kinds(args)
        if kinds is not None and (kernel, kinds) in self._settled:
            return False            # found cached by an earlier flight of this process
        signature = tuple(kernel.typeof_pyval(a) for a in args)
        if (kernel, signature) in self._queued:
            return False
        if cached(kernel, signature):
            if kinds is not None:
                self._settled.add((kernel, kinds))
            return False
        if self._folder is None:
            import atexit
            import tempfile
            self._folder = tempfile.mkdtemp(prefix="rocketsim-compiling-")
            self._owner = os.getpid()
            atexit.register(self.close)
        name = f"item-{priority:02d}-{self._count:04d}"
        self._count += 1
        part = os.path.join(self._folder, "part-" + name)     # written whole, then named
        with open(part, "wb") as stream:
            pickle.dump((kernel.__module__, kernel.__qualname__, signature), stream)
        os.replace(part, os.path.join(self._folder, name))
        self._queued[kernel, signature] = name
        self.kernels.add(kernel)
        self._start()
        return True

    def _start(self) -> None:
        """Start the second process unless it runs (it ends when idle)."""
        import subprocess
        import sys

        if self._process is not None and self._process.poll() is None:
            return
        package_parent = str(Path(__file__).resolve().parents[1])
        env = {**os.environ, "NUMBA_CACHE_DIR": cache_dir(),
               "PYTHONPATH": os.pathsep.join(filter(None, [package_parent, os.environ.get("PYTHONPATH")]))}
        try:
            self._process = subprocess.Popen(
                [sys.executable, "-c", "import sys; from rocketsim._jit import compile_queued; "
                 "compile_queued(sys.argv[1])", self._folder], env=env,
                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        except OSError:             # no process to spare: the kernels compile here
            self._process = None

    def _done(self, name: str) -> bool:
        return os.path.exists(os.path.join(self._folder, "done-" + name))

    def wait_for(self, kernel, signature: tuple) -> None:
        """Before this process compiles ``kernel`` for ``signature``: if it is queued and the
        second process has taken it, wait until it is compiled there (compiling the items
        not yet taken meanwhile), at most :data:`COMPILE_WAIT` s; else take it (compiled here)."""
        import time

        name = self._queued.pop((kernel, signature), None)
        if not any(queued is kernel for queued, _ in self._queued):
            self.kernels.discard(kernel)
        if name is None or self._done(name) or _claim(self._folder, name):
            return
        deadline = time.monotonic() + COMPILE_WAIT
        while not self._done(name) and time.monotonic() < deadline:
            if self._process is None or self._process.poll() is not None:
                return              # ended without it: compiled here
            if not self._compile_one():
                time.sleep(0.005)

    def compiling_elsewhere(self, kernel) -> bool:
        """Whether the second process has ``kernel`` to compile (an item of it queued, not yet
        done, the process running): a caller that can fly without it meanwhile (one step at a
        time, the same bits) does, instead of compiling it here or waiting for it."""
        if kernel not in self.kernels or self._process is None or self._process.poll() is not None:
            return False
        return any(queued is kernel and not self._done(name) for (queued, _), name in self._queued.items())

    def finish(self) -> None:
        """Have every queued kernel compiled into the cache (here those the second process has
        not taken, waiting for those it has: :meth:`wait_for`), then end the queue (:meth:`close`)."""
        import subprocess

        for kernel, signature in list(self._queued):
            self.wait_for(kernel, signature)
            kernel.compile(signature)
        self.close()
        if self._process is not None:       # idle now: it ends once the folder is gone
            try:
                self._process.wait(BESIDE_IDLE)
            except subprocess.TimeoutExpired:
                pass

    def _compile_one(self) -> bool:
        """Compile here the first queued item not yet taken; whether there was one."""
        for name in _queued_items(self._folder):
            item = _take_item(self._folder, name)
            if item is not None:
                _compile_item(self._folder, name, item)
                return True
        return False

    def close(self) -> None:
        """End the queue (at this process's exit): the folder removed (by the process that made
        it, not by a child forked from it). The second process takes nothing more; the kernel it
        is compiling it finishes into the cache, after this process has ended if need be (a
        flight shorter than its runs' compiling leaves them compiled for the next), and ends."""
        import shutil

        if self._owner != os.getpid():
            return
        if self._folder is not None:
            shutil.rmtree(self._folder, ignore_errors=True)
            self._folder = None
        self._queued.clear()
        self.kernels.clear()


BESIDE = CompiledBeside()


def compile_beside(kernel, args, priority: int = 0) -> None:
    """On a cold cache, queue ``kernel`` for the types of ``args`` for the second process
    (:class:`CompiledBeside`; lower ``priority`` first), unless :data:`COMPILE_BESIDE` is off."""
    if COMPILE_BESIDE:
        BESIDE.add(kernel, args, priority)


def compiling_elsewhere(kernel) -> bool:
    """Whether the second process is compiling ``kernel`` now (:meth:`CompiledBeside.compiling_elsewhere`)."""
    return BESIDE.compiling_elsewhere(kernel)


def finish_beside() -> None:
    """Have every kernel queued for the second process compiled into the cache and end the
    queue (:meth:`CompiledBeside.finish`): after a flight flown to fill the cache, which may
    have ended before its runs were compiled beside, in a process that ends without its
    exit handlers (a pool's worker)."""
    BESIDE.finish()
