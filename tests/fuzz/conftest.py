"""The fuzz tests' tally, printed at the end of the run (gathered from every xdist
worker when the suite runs on several processes)."""

import pytest
from hypothesis import settings

from tests.fuzz.harness import COUNTS, PEAKS


def pytest_sessionfinish(session):
    output = getattr(session.config, "workeroutput", None)
    if output is not None:          # an xdist worker: hand the tally to the controller
        output["fuzz_counts"] = dict(COUNTS)
        output["fuzz_peaks"] = dict(PEAKS)


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    output = getattr(node, "workeroutput", {})
    COUNTS.update(output.get("fuzz_counts", {}))
    for kind, rise in output.get("fuzz_peaks", {}).items():
        PEAKS[kind] = max(PEAKS.get(kind, 0), rise)


def pytest_terminal_summary(terminalreporter):
    if not COUNTS:
        return
    kinds = ", ".join(f"{kind} {n}" for kind, n in sorted(COUNTS.items()))
    peaks = ", ".join(f"{kind} {rise / 2**20:.0f} MiB" for kind, rise in sorted(PEAKS.items()))
    terminalreporter.write_line(
        f"fuzz ({settings.get_current_profile_name()} profile): {sum(COUNTS.values())} generated "
        f"inputs ({kinds}); largest rise of resident memory during one input: "
        f"{peaks or 'not measured'}")
