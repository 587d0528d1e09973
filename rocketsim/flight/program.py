"""Flight-computer programs: a Python file with ``main(fc)`` run as a sequential script.

The scheduling contract (decided here because it shapes the step loop):

* A program is a Python file defining ``main(fc)``. It is written as a plain
  sequential script; ``fc.step()``, ``fc.sleep(seconds)`` and
  ``fc.wait_until(predicate)`` hand control back to the simulator.
* The simulator resumes the program at most once per step, at the start of
  the step (before the physics), and runs it until its next hand-back. A
  program sleeping or waiting is not resumed until its wake-up time has come
  or its predicate (evaluated once per step) is true.
* When ``main`` returns, the program is finished; the vehicle flies on with
  its last commands.
* An exception in the program ends the flight with a :class:`ProgramError`
  naming the program's file and line; the telemetry written so far stays
  readable.
* A program that keeps control for more than its CPU budget in one step
  (default 1 s, ``program_cpu_budget`` in the scenario) is stopped the same
  way: an endless loop cannot hang the simulator. Time numba spends
  compiling or loading kernels (a cold cache) does not count, nor does the
  simulator's own first import of a library a call needs (:func:`not_counted`).
* So is a program that keeps control for more than its wall time in one
  wake-up (default 10 s, ``program_time_limit``), blocked or busy
  (:class:`~rocketsim.flight.leash.Leash`: in the main thread a sleep or a
  lock is interrupted too; in another thread a Python loop is). The CPU
  budget needs the main thread; the wall-time limit holds in any.
* A program is a plain function: a generator function, a coroutine function,
  a class or another callable object is refused when it is loaded.

The program runs in a greenlet in the simulator's own thread, so switching
is cheap (about a microsecond) and strictly alternating: the run is
deterministic.
"""

from __future__ import annotations

import contextlib
import functools
import inspect
from types import SimpleNamespace
import traceback
from pathlib import Path
from typing import Callable

import greenlet

from rocketsim.errors import InputError, signal_behind
from rocketsim.flight.arguments import truth
from rocketsim.flight.conditions import Condition
from rocketsim.flight.cpu_budget import COMPILING, CpuBudget, ProgramOverBudget
from rocketsim.flight.leash import Leash, Stop
from rocketsim.limits import MAX_TEXT_BYTES, read_bounded

# mission time tolerance for "the wake-up time has come" (s): steps are
# accumulated in floating point, a sleep of 1.0 s must wake after 50 x 0.02 s
WAKE_TOLERANCE = 1e-9


DEFAULT_CPU_BUDGET = 1.0   # s of CPU time one step of a program may use
DEFAULT_TIME_LIMIT = 10.0  # s of wall time one wake-up of a program may take


class ProgramError(InputError):
    """The flight program raised: names its file, line and the exception."""


class ProgramOverTime(BaseException):
    """Raised inside a program that kept control past its wall-time limit in one wake-up."""


def load_program(path: Path, entry: str = "main") -> Callable:
    """Compile and run a program file's top level; return its ``main`` (or the
    function named ``entry``), a plain function (:func:`plain_program`)."""
    main = getattr(load_program_module(path), entry, None)
    if not callable(main):
        raise ProgramError(f"the program defines no {entry}(fc) function", file=Path(path))
    return plain_program(main, path)


def plain_program(main: Callable, path: Path) -> Callable:
    """``main``, refused with a :class:`ProgramError` at its line unless it is a plain
    function: a generator or coroutine function would run none of its body when called,
    and a class or callable object is not a program the runner can locate."""
    code = getattr(main, "__code__", None)
    line = code.co_firstlineno if code is not None and Path(code.co_filename) == Path(path) else None
    kind = ("a generator function" if inspect.isgeneratorfunction(main) or inspect.isasyncgenfunction(main)
            else "a coroutine function (async def)" if inspect.iscoroutinefunction(main)
            else None if inspect.isfunction(main) or inspect.ismethod(main)
            else f"a {type(main).__name__} object")
    if kind is not None:
        raise ProgramError(f"the program's {getattr(main, '__name__', 'main')} is {kind}, not a plain "
                           "function: write it as 'def main(fc):' handing control back with fc.step(), "
                           "fc.sleep() or fc.wait_until()", file=Path(path), line=line)
    return main


def load_program_module(path: Path) -> SimpleNamespace:
    """Compile and run a program file's top level; return its names as attributes
    (``main`` None if it defines none). A program reuses another's functions this
    way, e.g. ``load_program_module(Path(__file__).parent / "orbit_ascent.py").ascend``:
    program files sit beside scenarios, not on the import path."""
    path = Path(path)
    try:
        source = read_bounded(path, MAX_TEXT_BYTES, "program").decode("utf-8")
    except UnicodeDecodeError as error:
        raise InputError(f"cannot read the program ({error})", file=path) from None
    try:
        code = _compiled(source, str(path))
    except SyntaxError as error:
        raise ProgramError(f"syntax error: {error.msg}", file=path, line=error.lineno,
                           column=error.offset) from None
    namespace = {"__name__": "rocketsim_program", "__file__": str(path)}
    try:
        exec(code, namespace)
    except BaseException as error:  # noqa: BLE001 - the user's code may raise anything
        if not _raised_by_program(error, path):
            raise
        raise _program_error(error, path) from None
    namespace.setdefault("main", None)
    return SimpleNamespace(**{k: v for k, v in namespace.items() if k != "__builtins__"})


@functools.lru_cache(maxsize=64)
def _compiled(source: str, filename: str):
    """The code object of a program's text (kept by text and file name: each flight of a
    campaign or a notebook loads its programs again, and compiling them was most of the
    cost of building a world; a code object is immutable, and each load
    runs it in a namespace of its own). A syntax error is raised again at every load."""
    return compile(source, filename, "exec")


def _raised_by_program(error: BaseException, path: Path) -> bool:
    """Whether ``error`` ends the program rather than the simulator: any Exception, a
    ``sys.exit()``, the CPU budget, or another BaseException the program's own code
    raises (GeneratorExit, its own classes); not Ctrl-C, nor what a signal handler
    raises while the program runs (SIGTERM's: they stop the flight as they would
    without a program)."""
    behind = signal_behind(error)       # raised inside a compiled kernel: a SystemError's cause
    if isinstance(behind, (KeyboardInterrupt, Stop)):
        return False
    if isinstance(behind, (Exception, SystemExit, ProgramOverBudget, ProgramOverTime)):
        return True
    frames = traceback.extract_tb(error.__traceback__)
    return bool(frames) and Path(frames[-1].filename) == path


def _deepest_line(frames, path: Path, line: int | None = None) -> int | None:
    """The line of the deepest of ``frames`` (a traceback's or a stack's) in ``path``, else ``line``."""
    for frame in frames:
        if Path(frame.filename) == path:
            line = frame.lineno
    return line


def _program_error(error: BaseException, path: Path, budget: float = 0.0,
                   line: int | None = None, limit: float = 0.0) -> ProgramError:
    """A :class:`ProgramError` pointing at the deepest line of ``path`` in the traceback
    (else at ``line``)."""
    line = _deepest_line(traceback.extract_tb(error.__traceback__), path, line)
    if isinstance(signal_behind(error), ProgramOverTime):
        return ProgramError(f"the program kept control for {limit:g} s of wall time in one wake-up "
                            "without handing it back (fc.step(), fc.sleep() or fc.wait_until()); is "
                            "it blocked (a sleep, a lock, a read) or in an endless loop? (raise the "
                            "limit with 'program_time_limit')", file=path, line=line)
    if isinstance(signal_behind(error), ProgramOverBudget):    # also when it ran out inside a kernel
        return ProgramError(f"the program ran {budget:g} s of CPU time in one step without handing "
                            "back control (fc.step(), fc.sleep() or fc.wait_until()); is it in an "
                            "endless loop? (raise the limit with 'program_cpu_budget')",
                            file=path, line=line)
    if isinstance(error, SystemExit):
        return ProgramError(f"the program called sys.exit({error.code!r}); a program ends by "
                            "returning from main(fc)", file=path, line=line)
    text = "".join(traceback.format_exception_only(type(error), error)).strip()
    return ProgramError(f"the program raised {text}", file=path, line=line)


class ProgramRunner:
    """Runs one program's ``main(fc)`` step by step in a greenlet."""

    def __init__(self, main: Callable, path: Path, cpu_budget: float = DEFAULT_CPU_BUDGET,
                 time_limit: float = DEFAULT_TIME_LIMIT):
        self.path = Path(path)
        self.cpu_budget = cpu_budget
        self.time_limit = time_limit
        self._budget = CpuBudget(cpu_budget)
        self._leash = Leash(time_limit, ProgramOverTime, paused=lambda: COMPILING.depth > 0)
        self._main = main
        self._greenlet: greenlet.greenlet | None = None
        self._wake_time = 0.0
        self._predicate: Callable[[], bool] | None = None
        self._predicate_line: int | None = None     # the program's line that handed it over
        self._checked: tuple | None = None          # (t, what due(t) gives: True, False or its error)
        self._watched = False                       # inside watched(): the condition's calls marked
        self._calls = 0                             # the condition's calls marked so far
        self.finished = False

    # --- called by the simulator -------------------------------------------
    def due(self, t: float) -> bool:
        """Whether the program is to run in the step starting at ``t`` (what :meth:`check`
        found for ``t``, if it was asked); raises the program's error its condition raised."""
        checked = self._checked
        if checked is None or checked[0] != t:
            self.check(t)
            checked = self._checked
        self._checked = None
        if isinstance(checked[1], ProgramError):
            raise checked[1]
        return checked[1]

    def check(self, t: float) -> bool:
        """Read now whether the program is to run in the step starting at ``t`` (woken at
        its time, or its condition true), the outcome (True, False or the program's error)
        kept for the call of :meth:`due` at ``t`` (a condition read ahead of the world's
        loop, once, as the loop reads it); True unless it is False. Inside
        :meth:`watched` each reading of the condition is marked for the budget and the
        time limit (armed once for the stretch), else they are armed around it."""
        predicate = self._predicate
        if self.finished or t + WAKE_TOLERANCE < self._wake_time:
            outcome = False
        elif predicate is None:
            outcome = True
        else:
            try:
                if self._watched:       # _timed's mark, here without its call: read at every step
                    budget, leash = self._budget, self._leash
                    self._calls = call = self._calls + 1
                    budget.call = leash.call = call
                    try:
                        outcome = predicate()
                    finally:
                        budget.call = leash.call = 0
                else:
                    outcome = self._timed(predicate)
                if outcome is not True and outcome is not False:
                    outcome = truth(outcome)
            except BaseException as error:  # noqa: BLE001
                if not _raised_by_program(error, self.path):
                    raise
                outcome = self._failed(error)
            else:
                if outcome:
                    self._predicate = None
        self._checked = (t, outcome)
        return outcome is not False

    def resume_due(self, fc, t: float, next_t: float) -> bool:
        """Inside a compiled run that reads the program after each of its steps, where
        :meth:`check` has found it due at ``t`` (its wake time reached, its condition true,
        or its condition's error kept): resume it now, ahead of the world's loop;
        :meth:`due` at ``t`` then says False (it has run) or raises the program's error.
        Returns whether the run must end at this step: the program's error, or, handed
        back, it waits on what such a run does not read at ``next_t`` (a compiled
        condition, a wake time after it) or has finished."""
        if self._checked[1] is not True:        # the error its condition raised
            return True
        try:
            self.resume(fc)
        except ProgramError as error:
            self._checked = (t, error)
            return True
        self._checked = (t, False)
        predicate = self._predicate
        if self.finished or isinstance(predicate, Condition):
            return True
        return predicate is None and next_t + WAKE_TOLERANCE < self._wake_time

    def _timed(self, function: Callable, *args):
        """``function(*args)``, the program's Python, under its CPU budget and time limit:
        inside :meth:`watched` the call is marked (both armed once for the stretch), else
        both are armed around it."""
        budget, leash = self._budget, self._leash
        if not self._watched:
            with budget, leash:
                return function(*args)
        self._calls = call = self._calls + 1
        budget.call = leash.call = call
        try:
            return function(*args)
        finally:
            budget.call = leash.call = 0

    def _failed(self, error: BaseException) -> ProgramError:
        """The program's error for ``error``, raised by its condition (at the condition's
        own line, else at that of fc.wait_until's call); the program is finished."""
        self.finished = True
        code = getattr(self._predicate, "__code__", None)
        line = (code.co_firstlineno if code is not None and Path(code.co_filename) == self.path
                else self._predicate_line)
        return _program_error(error, self.path, self.cpu_budget, line, self.time_limit)

    @contextlib.contextmanager
    def watched(self):
        """Context manager: the CPU budget and the wall-time limit armed once around many
        readings of the condition (:meth:`check` after every step of a compiled run), each
        reading timed on its own all the same (:meth:`CpuBudget.watch`,
        :meth:`~rocketsim.flight.leash.Leash.watch`). Either's exception landing just
        outside a reading (as it ended) is the program's error too."""
        self._budget.watch()
        self._leash.watch()
        self._watched = True
        try:
            yield
        except (ProgramOverBudget, ProgramOverTime) as error:
            raise self._failed(error) from None
        finally:
            self._watched = False
            self._leash.unwatch()
            self._budget.unwatch()

    def wake_time(self) -> float:
        """Earliest mission time the program may run again (inf when finished)."""
        if self.finished:
            return float("inf")
        return self._wake_time

    @property
    def waiting_on_predicate(self) -> bool:
        return self._predicate is not None

    @property
    def condition(self):
        """The compiled form of the condition waited on
        (:class:`~rocketsim.flight.conditions.Condition`'s ``code``), or None: not
        waiting, or on a plain function (read in Python every step)."""
        return self._predicate.code if isinstance(self._predicate, Condition) else None

    def resume(self, fc) -> None:
        """Run the program until it hands control back (or returns)."""
        if self._greenlet is None:
            self._greenlet = greenlet.greenlet(self._main)
            args = (fc,)
        else:
            args = ()
        try:
            self._timed(self._greenlet.switch, *args)
        except BaseException as error:  # noqa: BLE001
            if not _raised_by_program(error, self.path):
                raise
            self.finished = True
            raise _program_error(error, self.path, self.cpu_budget, limit=self.time_limit) from None
        if self._greenlet.dead:
            self.finished = True

    def close(self) -> None:
        """Abandon a program that has not finished (end of the flight)."""
        if self._greenlet is not None and not self._greenlet.dead:
            self._greenlet.throw()  # GreenletExit: finally blocks run
            self.finished = True

    # --- called from inside the program (through fc) ----------------------
    def hand_back(self, wake_time: float = 0.0, predicate: Callable[[], bool] | None = None) -> None:
        current = greenlet.getcurrent()
        if current is not self._greenlet:
            raise RuntimeError("fc.step()/sleep()/wait_until() called outside the flight program")
        self._wake_time = wake_time
        self._predicate = predicate
        if predicate is not None:
            self._predicate_line = _deepest_line(traceback.extract_stack(), self.path)
        current.parent.switch()



