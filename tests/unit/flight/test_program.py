"""The flight-computer scheduling contract (docs/how-to/programs.md)."""

import json
import re
import subprocess
import sys

import pytest

from rocketsim.errors import signal_behind
from rocketsim.flight.program import (ProgramError, ProgramOverBudget, _program_error,
                                      _raised_by_program, load_program_module)
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.telemetry.reader import messages, metadata


def logged(path):
    return [m["message"] for _, _, m in messages(path, ["/log"])]


def test_the_program_runs_exactly_once_per_step(scenario, tmp_path):
    program = """
    def main(fc):
        while True:
            fc.log(repr(fc.time))
            fc.step()
    """
    out = tmp_path / "run.mcap"
    fly(load(scenario(program, duration="1 s")), out)
    times = [float(m) for m in logged(out)]
    # one resume per 20 ms step, steps 0 .. 49, each once, at k * h exactly
    assert times == [k * 0.02 for k in range(50)]


def test_sleep_and_wait_until_wake_at_the_right_step(scenario, tmp_path):
    program = """
    def main(fc):
        fc.sleep(1.0)
        fc.log("woke", repr(fc.time))
        fc.wait_until(lambda: fc.time >= 1.5)
        fc.log("condition", repr(fc.time))
        fc.sleep(0.0)
        fc.log("zero sleep still yields", repr(fc.time))
    """
    out = tmp_path / "run.mcap"
    fly(load(scenario(program, duration="3 s")), out)
    assert logged(out) == ["woke 1.0", "condition 1.5", "zero sleep still yields 1.52"]


def test_a_program_that_raises_names_its_file_and_line_and_leaves_readable_telemetry(scenario, cli, tmp_path):
    program = """
    def main(fc):
        fc.sleep(0.5)
        fc.log("about to fail")
        return 1 / 0
    """
    path = scenario(program, duration="10 s")
    out = tmp_path / "run.mcap"
    result = cli("fly", path, "-o", out)
    assert result.exit_code == 2
    assert "Traceback" not in result.output
    assert "program.py:5" in result.output and "ZeroDivisionError" in result.output
    assert logged(out) == ["about to fail"]
    states = list(messages(out, ["/probe/state"]))
    assert states and states[-1][2]["t"] == pytest.approx(0.5)
    outcome = metadata(out)["outcome"]
    assert outcome["status"] == "error" and "ZeroDivisionError" in outcome["error"]


def test_a_program_with_a_syntax_error_is_refused_before_flight(scenario, tmp_path):
    path = scenario("def main(fc):\n    fc.step(\n")
    with pytest.raises(ProgramError) as caught:
        fly(load(path), tmp_path / "run.mcap")
    assert caught.value.file.endswith("program.py") and caught.value.line is not None


def test_a_program_loaded_again_runs_anew_and_an_edit_is_seen(tmp_path):
    # programs are compiled once per text (each flight of a campaign loads them again): a
    # second load runs the file's top level again in a namespace of its own, and the
    # file changed on disk is the new text, its syntax error reported at every load
    path = tmp_path / "program.py"
    path.write_text("runs = []\nruns.append(1)\nVALUE = 1\ndef main(fc):\n    pass\n")
    first, second = load_program_module(path), load_program_module(path)
    assert first.runs == [1] and second.runs == [1] and first.runs is not second.runs
    path.write_text("VALUE = 2\ndef main(fc):\n    pass\n")
    assert load_program_module(path).VALUE == 2
    path.write_text("def main(fc):\n    fc.step(\n")
    for _ in range(2):
        with pytest.raises(ProgramError, match="syntax error") as caught:
            load_program_module(path)
        assert caught.value.line is not None


def test_a_program_without_main_is_refused(scenario, tmp_path):
    with pytest.raises(ProgramError, match="main"):
        fly(load(scenario("x = 1\n")), tmp_path / "run.mcap")


def test_fc_step_outside_the_program_is_an_error(scenario, tmp_path):
    program = """
    def main(fc):
        fc.wait_until(lambda: fc.step())
    """
    with pytest.raises(ProgramError, match="outside the flight program"):
        fly(load(scenario(program)), tmp_path / "run.mcap")


def test_summary_json_lists_events_final_state_and_orbit(scenario, cli, tmp_path):
    program = """
    def main(fc):
        fc.sleep(2.0)
        fc.event("checkpoint", altitude_m=fc.altitude)
    """
    out, summary_path = tmp_path / "run.mcap", tmp_path / "summary.json"
    result = cli("fly", scenario(program), "-o", out, "--summary-json", summary_path)
    assert result.exit_code == 0, result.output
    summary = json.loads(summary_path.read_text())
    body = summary["bodies"]["probe"]
    assert [e["name"] for e in body["events"]] == ["checkpoint"]
    assert body["events"][0]["time_s"] == pytest.approx(2.0)
    assert 410e3 < body["events"][0]["altitude_m"] < 440e3
    # the start is in mean elements; the osculating inclination the summary reports
    # ripples about the mean 51.6 deg by up to (3/4) J2 (R/a)^2 sin i cos i = 0.020 deg
    assert body["orbit"]["inclination_deg"] == pytest.approx(51.6, abs=0.021)
    assert body["final"]["time_s"] == pytest.approx(10.0)
    assert "checkpoint" in result.output


def _fly_over_budget(scenario, cli, tmp_path, program, budget):
    """Fly ``program`` for 10 s under a CPU ``budget``; it must end with exit status 2."""
    path = scenario(program, duration="10 s", extra=f"program_cpu_budget: {budget}\n")
    out = tmp_path / "run.mcap"
    result = cli("fly", path, "-o", out)
    assert result.exit_code == 2
    return out, result


def test_a_program_that_never_hands_back_is_stopped_by_its_cpu_budget(scenario, cli, tmp_path):
    program = """
    def main(fc):
        fc.sleep(0.2)
        while True:
            try:
                pass
            except Exception:
                pass
    """
    out, result = _fly_over_budget(scenario, cli, tmp_path, program, "0.3 s")
    # stopped somewhere inside the endless loop (lines 4 to 8 of the program)
    assert re.search(r"program\.py:[4-8]: the program ran 0\.3 s of CPU time", result.output)
    states = list(messages(out, ["/probe/state"]))
    assert states[-1][2]["t"] == pytest.approx(0.2)          # telemetry intact up to the stop
    assert metadata(out)["outcome"]["status"] == "error"


def test_the_integrator_is_imported_at_the_first_prediction_outside_the_budget(scenario, write, tmp_path):
    # scipy's integrator (fc.predict's) takes ~0.15 s of CPU to import: a flight that
    # predicts nothing must not import it, and a program whose first step predicts
    # under a 0.05 s budget must not be stopped for the import. In a fresh interpreter,
    # where nothing has imported it yet.
    sleeper = scenario("def main(fc):\n    fc.sleep(0.5)\n", duration="1 s")
    write("predicts.py", """\
        def main(fc):
            t, r, v = fc.predict(60.0)
            fc.event("predicted", t=t, radius_m=float((r @ r) ** 0.5))
        """)
    predictor = write("predicting.yaml", "name: predicting\nvehicle: vehicle.yaml\nmission: mission.yaml\n"
                                          "program: predicts.py\nprogram_cpu_budget: 0.05 s\n")
    script = """
import sys
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
fly(load(sys.argv[1]), sys.argv[3])
print("imported after a flight without predictions:", "scipy.integrate" in sys.modules)
summary = fly(load(sys.argv[2]), sys.argv[4])
print("events:", [(e["name"], round(e["time_s"], 3)) for e in summary["bodies"]["probe"]["events"]])
"""
    result = subprocess.run([sys.executable, "-c", script, str(sleeper), str(predictor), str(tmp_path / "a.mcap"),
                             str(tmp_path / "b.mcap")], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert "imported after a flight without predictions: False" in result.stdout
    assert "events: [('predicted', 0.0)]" in result.stdout


def test_a_program_predicting_in_an_endless_loop_is_stopped_by_its_cpu_budget(scenario, tmp_path):
    # the integrator's first import is kept out of the budget, which then starts afresh:
    # only the first time, or a loop of predictions would never be stopped. In a fresh
    # interpreter (the import not yet made), with a timeout in case it is not stopped.
    path = scenario("def main(fc):\n    while True:\n        fc.predict(1.0)\n", duration="1 s",
                    extra="program_cpu_budget: 0.5 s\n")
    result = subprocess.run([sys.executable, "-m", "rocketsim_cli.main", "fly", str(path), "-o",
                             str(tmp_path / "run.mcap")], capture_output=True, text=True, timeout=120)
    assert result.returncode == 2, result.stderr
    assert re.search(r"program\.py:[23]: the program ran 0\.5 s of CPU time", result.stderr + result.stdout)


def test_a_signal_inside_a_compiled_kernel_is_read_as_the_signal(tmp_path):
    # a budget's timer or Ctrl-C landing while a compiled kernel runs surfaces as numba's
    # SystemError with the signal's exception as its cause: the program's error must
    # read as the budget, and Ctrl-C must stop the simulator, not end the program
    path = tmp_path / "program.py"
    over = SystemError("CPUDispatcher(<function bodies_at>) returned a result with an exception set")
    over.__cause__ = ProgramOverBudget()
    assert _raised_by_program(over, path)
    assert "the program ran 0.5 s of CPU time in one step" in str(_program_error(over, path, 0.5))
    interrupted = SystemError("returned a result with an exception set")
    interrupted.__cause__ = KeyboardInterrupt()
    assert not _raised_by_program(interrupted, path)
    assert isinstance(signal_behind(interrupted), KeyboardInterrupt)
    assert signal_behind(ValueError("x")).args == ("x",)


def test_compiling_a_kernel_does_not_count_against_the_cpu_budget(scenario, cli, tmp_path):
    # a cold numba cache compiles kernels inside a program's step: the program
    # below compiles a fresh kernel (numba, no disk cache: ~0.1-0.5 s of CPU)
    # under a 0.02 s budget and must not be stopped for it, while the same
    # budget still stops the busy loop that follows
    program = """
    import numba

    def main(fc):
        @numba.njit(cache=False)
        def busy(n):
            total = 0.0
            for i in range(n):
                total += (i % 7) * 0.5
            return total
        fc.log(f"compiled: {busy(10)}")
        fc.step()
        while True:
            pass
    """
    out, result = _fly_over_budget(scenario, cli, tmp_path, program, "0.02 s")
    assert "compiled: 12.0" in logged(out)
    assert re.search(r"program\.py:1[34]: the program ran 0\.02 s of CPU time", result.output), result.output
