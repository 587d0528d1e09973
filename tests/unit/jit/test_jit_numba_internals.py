"""numba's private API as rocketsim uses it (:mod:`rocketsim.jit.numba_internals`): the
numba installed is a tested release within pyproject.toml's pin, every patch is in place,
each does what it claims (checked against numba without it), and a numba that lacks or
changed an internal fails loudly, naming its version."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import tomllib
import warnings
from pathlib import Path

import numba
import numpy as np
import pytest
from numba.core import caching, sigutils

from rocketsim.jit import njit, numba_internals
from rocketsim.jit.numba_internals import NumbaChanged, UntestedNumba, applied, check
from tests.cold_cache import cold_env, on_a_cold_cache

ROOT = Path(__file__).resolve().parents[3]


def _numba_requirement() -> str:
    dependencies = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    return next(d for d in dependencies if re.match(r"numba\b", d))


def test_numba_is_pinned_to_the_tested_releases_and_is_one_of_them():
    first, last = numba_internals.TESTED[0], numba_internals.TESTED[-1]
    major, minor = last.split(".")
    assert _numba_requirement() == f"numba>={first},<{major}.{int(minor) + 1}"
    assert numba_internals.tested(numba.__version__), \
        f"numba {numba.__version__} is not a tested release {numba_internals.TESTED}"
    with warnings.catch_warnings():
        warnings.simplefilter("error")          # no UntestedNumba, no other warning
        check()


def test_every_patch_is_applied():
    @njit(cache=True)
    def halved(x):
        return 0.5 * x

    assert halved(3.0) == 1.5
    assert applied(halved) == {"own callees": True, "optimisation level": True, "cache folder": True,
                               "plain call templates": True, "compiled once": True, "locked saves": True,
                               "damaged files read as missing": True}


def test_a_missing_internal_fails_loudly_naming_numba_and_the_internal(monkeypatch):
    monkeypatch.delattr(sigutils, "normalize_signature")
    with pytest.raises(NumbaChanged, match=rf"numba {re.escape(numba.__version__)} .*"
                                           r"numba\.core\.sigutils\.normalize_signature is missing"):
        check()


def test_a_changed_internal_fails_loudly(monkeypatch):
    monkeypatch.setattr(caching.FunctionCache, "_index_key", lambda self, sig: None)
    with pytest.raises(NumbaChanged, match=r"FunctionCache\._index_key takes \('self', 'sig'\), "
                                           r"not \('self', 'sig', 'codegen'\).*pip install 'numba>="):
        check()


def test_an_untested_numba_warns(monkeypatch):
    monkeypatch.setattr(numba_internals, "_numba_version", lambda: "0.99.0")
    with pytest.warns(UntestedNumba, match=r"numba 0\.99\.0 is not a release rocketsim was tested with"):
        check()


# Two kernels, the second calling the first (whose reference counting numba's runtime
# functions do, linked into the caller's module); the final module's definitions.
_TWO_KERNELS = """
import json, re, sys
import numpy as np
if sys.argv[1] == "rocketsim":
    from rocketsim.jit import njit
    compile = njit(cache=False)
else:
    import numba
    compile = numba.njit
@compile
def inner(a, n):
    s = 0.0
    for i in range(n):
        s += a[i % a.shape[0]] * i
    return s
@compile
def outer(a):
    return inner(a[1:], 3) + inner(a, 5) * 2.0
outer(np.arange(4.0))
ir = outer.inspect_llvm(outer.signatures[0])
print(json.dumps(re.findall(r"^define (linkonce_odr|internal)\\b.*?@([\\w.]+)\\(", ir, re.M)))
"""


def _definitions(how: str, tmp_path) -> dict[str, str]:
    done = subprocess.run([sys.executable, "-c", _TWO_KERNELS, how], capture_output=True, text=True,
                          env=cold_env(tmp_path, NUMBA_OPT="1"), timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    return {name: linkage for linkage, name in json.loads(done.stdout.strip().splitlines()[-1])}


def test_a_kernels_callees_are_internal_to_its_machine_code(tmp_path):
    """numba links the functions a kernel calls into its module as weak definitions
    (linkonce_odr), which the JIT binds to the first copy loaded anywhere; rocketsim's kernel
    holds them internal. numba alone, at the same optimisation level, keeps them weak."""
    ours, numbas = _definitions("rocketsim", tmp_path), _definitions("numba", tmp_path)
    assert {"NRT_incref", "NRT_decref"} <= set(numbas) and set(numbas.values()) == {"linkonce_odr"}
    assert {name: ours[name] for name in numbas} == {name: "internal" for name in numbas}
    assert "linkonce_odr" not in ours.values()


def test_a_constant_argument_is_typed_as_its_kind_one_signature_for_every_constant():
    """A kernel calling another with the constants 2 and 3 compiles the callee once, for
    int64; numba alone compiles it once per literal value. A callee that can only be typed
    with the literal (a tuple indexed by it) keeps the literal."""
    def scaled(x, n):
        return x * n

    def both(x):
        return scaled_kernel(x, 2) + scaled_kernel(x, 3)

    def pick(t, k):
        return t[k]

    def picks(x):
        return pick_kernel((x, np.zeros(2)), 0)

    for compile in (njit(cache=False), numba.njit):
        scaled_kernel = compile(scaled)
        pick_kernel = compile(pick)
        assert compile(both)(1.5) == 7.5 and compile(picks)(2.0) == 2.0
        signatures = [str(s[1]) for s in scaled_kernel.signatures], [str(s[1]) for s in pick_kernel.signatures]
        if compile is numba.njit:
            assert signatures == (["Literal[int](2)", "Literal[int](3)"], ["Literal[int](0)"])
        else:
            assert signatures == (["int64"], ["Literal[int](0)"])


_TOTAL = """
import numpy as np
from rocketsim.jit import njit
@njit(cache=False)
def total(a):
    s = 0
    for i in range(a.shape[0]):
        s += a[i] * (i % 7)
    return s
total(np.arange(10))
print(total.inspect_llvm(total.signatures[0]).count("\\n"))
"""


def test_kernels_are_optimised_at_level_one_unless_numba_opt_says_otherwise(tmp_path):
    # the optimised machine code of one kernel: by default as NUMBA_OPT=1 makes it, not as
    # numba's own default (3)
    def lines(**opt: str) -> str:
        env = cold_env(tmp_path)
        env.pop("NUMBA_OPT", None)
        done = subprocess.run([sys.executable, "-c", _TOTAL], capture_output=True, text=True,
                              env={**env, **opt}, timeout=300)
        assert done.returncode == 0, done.stderr[-3000:]
        return done.stdout.strip().splitlines()[-1]

    default, one, three = lines(), lines(NUMBA_OPT="1"), lines(NUMBA_OPT="3")
    assert default == one != three


_INDEXED = """
import json, os
from rocketsim.jit import njit
from rocketsim.jit.numba_internals import cached, cached_signatures, numba_types

@njit
def third(x):
    return x / 3.0

signature = numba_types(third, (1.0,))
before = cached(third, signature)
if os.environ["CALL"] == "1":
    third(1.0)
print(json.dumps([before, cached(third, signature), [str(s) for s in cached_signatures(third)],
                  third.signatures == []]))
"""


def test_the_cache_index_names_the_signatures_saved(tmp_path):
    """In a fresh process on an empty cache a kernel's signature is not cached until it is
    compiled; in the next process the index names it before anything is loaded."""
    first = json.loads(on_a_cold_cache(tmp_path, _INDEXED, CALL="1"))
    assert first == [False, True, ["(float64,)"], False]
    second = json.loads(on_a_cold_cache(tmp_path, _INDEXED, CALL="0"))
    assert second == [True, True, ["(float64,)"], True]     # named by the index, nothing loaded


def test_a_signature_with_a_c_function_pointer_is_pickled_and_read_back():
    """A compiled run's signature holds a C function pointer's type, whose typing template
    is a class made at run time: the standard pickler refuses it, numba's own (the queue of
    kernels compiled beside) writes it so that ``pickle`` reads back an equal signature."""
    import ctypes
    import pickle

    prototype = ctypes.CFUNCTYPE(None, ctypes.c_int64)
    function = prototype(lambda k: None)
    signature = (numba.typeof(np.zeros(3)), numba.typeof(function))
    with pytest.raises(pickle.PicklingError):
        pickle.dumps(signature)
    assert pickle.loads(numba_internals.serialized(("module", "kernel", signature))) == ("module", "kernel", signature)
