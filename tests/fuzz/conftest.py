"""The fuzz tests' tally, printed at the end of the run."""

from hypothesis import settings

from tests.fuzz.harness import COUNTS, PEAKS


def pytest_terminal_summary(terminalreporter):
    if not COUNTS:
        return
    kinds = ", ".join(f"{kind} {n}" for kind, n in sorted(COUNTS.items()))
    peaks = ", ".join(f"{kind} {rise / 2**20:.0f} MiB" for kind, rise in sorted(PEAKS.items()))
    terminalreporter.write_line(
        f"fuzz ({settings.get_current_profile_name()} profile): {sum(COUNTS.values())} generated "
        f"inputs ({kinds}); largest rise of resident memory during one input: "
        f"{peaks or 'not measured'}")
