"""The one way the library compiles its kernels (numba), one module per job.

=================================  ==========================================================
:mod:`~rocketsim.jit.kernel`       the decorator :func:`njit`, the :class:`Kernel` it makes,
                                   :func:`copy_into`
:mod:`~rocketsim.jit.entries`      compiled entries: :func:`entry_point`, :class:`Entries`
:mod:`~rocketsim.jit.settings`     every environment variable read (``ROCKETSIM_JIT``,
                                   ``ROCKETSIM_CACHE_DIR``, ``NUMBA_OPT``...)
:mod:`~rocketsim.jit.cache`        the cache folder named for the source's hash, its lock,
                                   each kernel compiled once among processes
:mod:`~rocketsim.jit.numba_internals`  every use of numba's private API, checked against the
                                   numba it was written for
:mod:`~rocketsim.jit.beside`       the optional second process compiling a cold cache's
                                   kernels (``ROCKETSIM_COMPILE_BESIDE=1``)
=================================  ==========================================================

Writing a kernel
----------------

A kernel is a function of numbers and arrays decorated with :func:`njit` (imported
from here); its module becomes part of the cache's key (:mod:`rocketsim.jit.cache`).
The options say how it is compiled:

* ``@njit``: a kernel of its own, counting references to the arrays it holds;
* ``@njit(inline="always")``: a few operations typed and inlined in each caller (numba's
  IR), no kernel of its own;
* ``@njit(borrows=True)``: without reference counting, for a kernel that makes no array
  and returns none (the derivative and the forces it sums): numba counts a reference to
  every array of every argument a kernel binds, an atomic increment and decrement each,
  which were a third of an RK4 step's time for a staged vehicle's some 35 arrays. numba
  refuses to compile such a kernel if it makes an array; one that returned an array would
  hand its caller a reference it never counted, and tests/unit/jit/test_jit_borrows.py checks every
  borrowing kernel's compiled return types. Every other kernel counts its references (not
  inherited from a borrowing caller), so which callees count does not depend on the order
  of compiling; ``forceinline=True`` asks LLVM to inline it as well;
* ``@njit(nogil=True)``: the compiled runs of many steps and the telemetry's framing
  release the GIL while they run, so that the telemetry's writing thread
  (:mod:`rocketsim.telemetry.writing_thread`) runs its Python beside them. The calls of
  one or a few steps keep it: released and taken again every step, it would hand it to
  the writing thread and back tens of times a batch of samples.

``fastmath`` stays off (results IEEE-exact, bit-identical run to run and at every
optimisation level) and division by zero gives inf or nan as numpy's does.

Four ways to call a kernel
--------------------------

1. ``kernel(*args)`` from Python: numba's dispatcher types every argument at every
   call (for a staged vehicle's named tuple of arrays, longer than a derivative takes):
   for calls made now and then.
2. ``entry_point(kernel, *args)``: the compiled entry for the arguments' types, bound
   once (kept by the arguments' kinds) and held by the caller, which calls it with
   arguments of the same types (the telemetry writer's framing, a sample's figures).
3. ``Entries.call(kernel, key, *args)``: the entries of one owner (a body, a vehicle's
   control), bound again when ``key`` (the vehicle's arrays, replaced at staging) is a
   new object: the calls made every step from Python.
4. From another kernel: a compiled call, or the callee inlined (``inline="always"``).

Five ways arrays are passed
---------------------------

1. **Read, numbers out**: borrowing kernels read the state ``y``, the parameters ``p``
   and the vehicle's arrays and return floats or tuples of floats.
2. **A new array returned**: a counting kernel makes its result (``advance`` returns a
   new state; ``figures`` a sample's row); the caller's arrays are left as they were.
3. **Into the caller's array**: ``*_into(out, ...)`` kernels write their result into
   ``out`` (or a row of it), with scratch arrays the caller made once (``step_into``'s
   stages ``k`` and parts ``work``); an array goes into a slice through
   :func:`copy_into`, never ``a[i:j] = b`` (whose shape check's error message is long to
   compile; tests/unit/jit/test_jit_kernel.py scans for it).
4. **Rows of a run**: a compiled run fills the rows of its caller's buffer (a sample
   each) and returns how many it filled (``coast_run``, ``fly_run``).
5. **Updated in place**: the few arrays that are state carried from call to call: a
   run's ``carry``, a stage marked dry in the vehicle's ``stage`` array, the other bodies'
   positions held in ``p`` (``hold_field``).

Flat arrays are read through named slots (``rocketsim.layout``, each array's constants
with a prefix of their own, docs/architecture.md); a staged vehicle's arrays travel as one
named tuple (``VehicleArrays``).

Running a kernel as plain Python, to debug it
---------------------------------------------

``ROCKETSIM_JIT=python`` (:mod:`rocketsim.jit.settings`) runs every kernel as the Python
function it is written as: ``breakpoint()`` or a debugger's breakpoint inside a kernel
stops there, ``print`` prints, and an error is a Python exception with a traceback into the
kernel's source (an index past an array's end raises ``IndexError``, where the compiled
kernel checks no bounds)::

    ROCKETSIM_JIT=python rocketsim fly scenarios/hobby-rocket.yaml --duration 1s -o debug.mcap

A flight so runs far slower than compiled: fly seconds of it, not a mission.
The one kernel that calls a numba intrinsic (machine code with no Python form: the
telemetry's block copy) is compiled all the same. Where Python and numba's numpy error
model differ, Python raises: a float divided by zero (``ZeroDivisionError``) or the square
root of a negative number (``math.sqrt``: ``ValueError``) stops the flight where the compiled kernel would
go on with inf or nan. Without the switch, any kernel's ``py_func`` is its Python function,
to call on its own (a notebook, a test).

Which numba
-----------

pyproject.toml pins numba to the releases :mod:`rocketsim.jit.numba_internals` was tested
with; a numba that lacks or changed an internal it patches stops the first compile with
:class:`~rocketsim.jit.numba_internals.NumbaChanged`, naming numba's version and what
changed, rather than running slower kernels in silence.
"""

from rocketsim.jit.beside import compile_beside, compiling_elsewhere, finish_beside
from rocketsim.jit.cache import cache_dir
from rocketsim.jit.entries import Entries, entry_point
from rocketsim.jit.kernel import Kernel, copy_into, njit

__all__ = ["Entries", "Kernel", "cache_dir", "compile_beside", "compiling_elsewhere", "copy_into",
           "entry_point", "finish_beside", "njit"]
