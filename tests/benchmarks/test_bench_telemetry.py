"""Benchmark: what telemetry costs, and how fast a run is summarised.

Printed (run with ``pytest -s``):
1. a flight's wall time with 10 Hz telemetry over the same flight without
   any (``World.run(None)``: no samples, no file) -- target at most 1.10.
   Four flights: the shipped spaceport-ballistic mission (its program runs
   every 20 ms step), the first 40 s of the shipped Falcon 9-class mission
   (a staged vehicle: program, autopilot and checks every step, as in the
   whole mission), its first 230 s (the upper stage, the booster and the
   fairing's halves: several bodies' samples in turn, each batch handed to
   the writer mixing their templates, as for most of the whole mission)
   and a program-less orbital coast (whole sample intervals
   flown and their figures computed in compiled runs, :mod:`rocketsim.sim.coast_runs`,
   so the writing is nearly all the work). For each, what
   one sample costs on its own: its numbers (``sampling.values``: one compiled
   call, in a loop at the flight's end) and their writing (the flight's own
   samples written again into a new file by ``TelemetryWriter.sample``:
   ``orjson`` formats the numbers, one compiled call splices them into the
   state, transform and location messages' templates and frames the MCAP
   records in the chunk; the chunks' zstd compression and index included).
   The flight's own samples, not one sample written over and over: zstd
   compresses repeated records to almost nothing, which would time the
   writing at about half its cost in a flight (ballistic 4.1 against 8.6 us,
   falcon9 5.5 against 11.1 us).
   For the coast, the floor of the encoding: the sample's numbers as JSON and
   its bytes compressed and checksummed, against the 10 % budget (a tenth of
   the flight's time per sample).
   Last figures (load 0.7-1.1): ballistic 1.26-1.28, falcon9 40 s 1.12-1.16,
   falcon9 230 s 1.16-1.20 (11-13 us per sample), coast 5.0-5.4; the whole
   mission (measured apart, best of 7) 1.21-1.24, of which a writer that does
   nothing leaves 1.11-1.12: half the cost is on the flight's thread (the runs'
   samples' figures, some 2.5 us a sample, and handing them over), half the
   writing thread's Python holding the GIL the flight's Python needs (its zstd,
   CRC and compiled framing release it). A sample's writing on its own (one by
   one, to the end of the writing thread's work) 8-12 us. The file's fixed cost
   1.2-2.1 ms is 8 % of the 22 ms ballistic flight and of the 26 ms 40 s one.
   Earlier figures (2-core machine shared with other jobs, load 5.9-6.1, flown
   alternately with the writer before the present one, in brackets): median
   ratio of the pairs ballistic 1.29-1.33 (1.31-1.42), falcon9 1.07-1.29
   (1.07-1.15), coast 2.77-2.88 (3.07-3.73); a sample's writing on its own
   ballistic 5.2-6.3 us (10.4-15.3), coast 20-28 us (22-26). Under such a
   load one flight's time swings by a factor of 2-4: only the ballistic
   writing's halving is beyond the noise. The coast's floor per sample: 34
   numbers as JSON 1.0-1.5 us, 1.8 kB of records compressed 5.4-6.5 us and
   checksummed 0.4-0.6 us (at load 2.2: 1.4, 5.6 and 0.4 us) against a
   budget of 1-3 us: with JSON in zstd chunks on the flight's thread the
   coast's ratio cannot come under ~1.45, whatever the code around it. With
   the coast's compiled runs (load 0.8): 150 s flown in 3.2 ms without
   telemetry, 19.5 ms with, ratio 6.0; its floor 5.6 us per sample against
   2 us of flight per interval (ratio at least 3.6): the encoding, not the
   flight, is the coast's cost, and even a writer on the second core would
   leave the flight waiting for it. The
   flights take 12-150 ms, so one
   run's ratio swings by 0.1-0.3 on a shared machine: each is flown in
   alternating pairs (9, 5 for falcon9), the ratio of the best times printed
   with the median of the pairs' ratios beside it;
2. ``rocketsim replay``'s summary of a one-hour 10 Hz flight's MCAP
   (target under 1 s), against reading every message of the same file.
Nothing asserts a time; the checks are that both flights end in the same
state and that the summary counts every message.
"""

import math
import statistics
import time
import zlib
from pathlib import Path

import orjson
import zstandard
from mcap.reader import make_reader
from mcap.records import Chunk
from mcap.stream_reader import StreamReader

from rocketsim.scenario.load import load
from rocketsim.sim import sampling
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.sim.build import build_world
from rocketsim.telemetry.mcap_stream import ZSTD_LEVEL
from rocketsim.telemetry.reader import read_run
from rocketsim.telemetry.sample_plans import interleaved_samples
from rocketsim.telemetry.writer import TelemetryWriter
from tests.benchmarks.timing import best_of

ROOT = Path(__file__).resolve().parents[2]


def _on_off(loaded, duration, out, pairs=9):
    """Wall times (s) of the flight without and with telemetry, flown in ``pairs``
    alternating pairs (a busy machine slows both alike): the best of each and the
    median of the pairs' ratios (how noisy the ratio is: a flight of 10-100 ms is
    easily disturbed); the file's fixed cost (a one-step flight with telemetry less
    one without: opening, attachments, metadata, summary, and what the first sample
    builds, e.g. the day's air table); the final state flown without telemetry; and
    what one sample costs on its own (:func:`_one_sample`)."""
    def off(seconds=duration):
        world = build_world(loaded, duration=seconds)
        world.run(None)
        return world

    def on(seconds=duration):
        fly(loaded, out if seconds == duration else out.with_suffix(".step.mcap"), duration=seconds)
        return out

    off()                                   # compile and warm both paths
    fly(loaded, out, duration=1.0)
    step = loaded.scenario.step
    t_off = t_on = float("inf")
    ratios = []
    for _ in range(pairs):
        t, world = best_of(1, off)
        t_off = min(t_off, t)
        ratios.append(best_of(1, on)[0] / t)
        t_on = min(t_on, ratios[-1] * t)
    t_file = best_of(5, lambda: on(step))[0] - best_of(5, lambda: off(step))[0]
    return (t_off, t_on, statistics.median(ratios)), world.bodies[0].y.copy(), t_file, \
        _one_sample(world, out.with_suffix(".loop.mcap"), loaded, duration)


def _one_sample(world, path, loaded, duration, calls=1000):
    """Best seconds per sample of what the flight calls per sample: its numbers
    (``sampling.values``, for the first body at the end of ``world``'s flight, called
    ``calls`` times) and their writing (``TelemetryWriter.sample`` of the flight's own
    samples, kept by :class:`_Kept`, into a new file, one by one, to the end of the
    writing thread's work, less the same file without samples: the same sample written
    again and again would compress to almost nothing, so chunks would seem nearly free)."""
    body = world.bodies[0]
    t_values = best_of(5, lambda: [sampling.values(body, world.gmst0, world.where) for _ in range(calls)])[0]
    kept = _Kept()
    build_world(loaded, duration=duration).run(kept)

    def write(samples):
        with TelemetryWriter(path, 0) as telemetry:
            for name in dict.fromkeys(sample[0] for sample in kept.kept):     # in the flight's order
                telemetry.add_body(name)
            start = time.perf_counter()
            for sample in samples:
                telemetry.sample(*sample)
        return time.perf_counter() - start      # the writing thread's work too, to the file's end

    # less the same file without samples: its end (summary, index) is the fixed cost
    t_write = min(write(kept.kept) for _ in range(5)) - min(write([]) for _ in range(5))
    return t_values / calls, t_write / len(kept.kept)


class _Kept:
    """A flight's telemetry that keeps its samples ``(body, numbers, layout, leaving)``
    and writes nothing."""

    def __init__(self):
        self.kept = []

    def add_body(self, name):
        pass

    def sample(self, body, values, fields, leaving=False):
        self.kept.append((body, values, fields, leaving))

    def sample_rows(self, body, rows, fields):
        self.kept.extend((body, values, fields, False) for values in rows)

    def sample_interleaved(self, blocks):
        self.kept.extend((*sample, False) for sample in interleaved_samples(blocks))

    def event(self, *args):
        pass

    def log(self, *args):
        pass


def _report(name, duration, times, t_file, one_sample):
    t_off, t_on, median = times
    samples = duration * 10
    print(f"\n{name}: {duration:g} s flown in {t_off * 1e3:.1f} ms without telemetry, "
          f"{t_on * 1e3:.1f} ms with 10 Hz telemetry: ratio {t_on / t_off:.2f} (best of each; "
          f"median of the pairs {median:.2f}; {(t_on - t_off) / samples * 1e6:.0f} us per sample; "
          f"the file's fixed cost {t_file * 1e3:.1f} ms, so {(t_on - t_off - t_file) / samples * 1e6:.0f} "
          f"us per sample beyond it; on its own a sample's numbers take {one_sample[0] * 1e6:.1f} us "
          f"and their writing {one_sample[1] * 1e6:.1f} us; the flight {t_off / samples * 1e6:.0f} us "
          f"per sample interval)")


def test_telemetry_on_versus_off(tmp_path, scenario):
    shipped = load(ROOT / "scenarios" / "spaceport-ballistic.yaml")
    times, y_off, t_file, one = _on_off(shipped, 20.0, tmp_path / "ballistic.mcap")
    _report("spaceport-ballistic (program every step)", 20.0, times, t_file, one)
    with open(tmp_path / "ballistic.mcap", "rb") as stream:
        last = list(make_reader(stream).iter_messages(topics=["/sounding-payload/state"]))[-1]
    import json
    assert json.loads(last[2].data)["position"] == y_off[:3].tolist()   # same flight either way

    falcon = load(ROOT / "scenarios" / "falcon9-leo.yaml")
    times, _, t_file, one = _on_off(falcon, 40.0, tmp_path / "falcon9.mcap", pairs=5)
    _report("falcon9-leo, first 40 s (staged vehicle: program, autopilot, checks every step)",
            40.0, times, t_file, one)

    times, _, t_file, one = _on_off(falcon, 230.0, tmp_path / "falcon9-bodies.mcap", pairs=3)
    _report("falcon9-leo, first 230 s (from 134 s two, from 200 s four bodies, sampled in turn)",
            230.0, times, t_file, one)

    coast = load(scenario(duration="150 s"))
    times, _, t_file, one = _on_off(coast, 150.0, tmp_path / "coast.mcap")
    _report("orbital coast, no program (compiled runs of sample intervals)", 150.0, times, t_file, one)
    _floor(coast, 150.0, tmp_path / "coast.mcap", times[0])


def _floor(loaded, duration, path, t_off):
    """Print what the file's encoding itself costs per sample of the flight (``path``
    its telemetry): its numbers formatted as JSON (one ``orjson.dumps`` of the
    sample's float64 numbers) and its bytes compressed (the file's chunks, again at
    the writer's zstd level) and checksummed (CRC-32), against the 10 % budget."""
    world = build_world(loaded, duration=duration)
    world.run(None)
    values, _ = sampling.values(world.bodies[0], world.gmst0, world.where)
    calls = 1000
    t_json = best_of(5, lambda: [orjson.dumps(values, option=orjson.OPT_SERIALIZE_NUMPY)
                                 for _ in range(calls)])[0] / calls
    with open(path, "rb") as stream:
        chunks = [zstandard.ZstdDecompressor().decompress(r.data, max_output_size=r.uncompressed_size)
                  for r in StreamReader(stream, emit_chunks=True).records if isinstance(r, Chunk)]
    compressor = zstandard.ZstdCompressor(level=ZSTD_LEVEL)
    t_zstd = best_of(3, lambda: [compressor.compress(c) for c in chunks])[0]
    t_crc = best_of(3, lambda: [zlib.crc32(c) for c in chunks])[0]
    samples = duration * 10 + 1
    size = sum(len(c) for c in chunks) / samples
    floor = t_json + (t_zstd + t_crc) / samples
    print(f"  its encoding's floor per sample: {values.size} numbers as JSON {t_json * 1e6:.2f} us, "
          f"{size:.0f} bytes of records compressed {t_zstd / samples * 1e6:.2f} us and checksummed "
          f"{t_crc / samples * 1e6:.2f} us: {floor * 1e6:.1f} us, against a budget of "
          f"{0.1 * t_off / samples * 1e6:.1f} us (10 % of the flight per sample): ratio at least "
          f"{1 + floor * samples / t_off:.2f} before the figures are computed or anything is called")


def _one_hour_file(path: Path) -> int:
    """A 10 Hz hour of a circular orbit, through the real writer (no flight needed)."""
    n = 36_001
    with TelemetryWriter(path, 1_795_694_400 * 10**9) as telemetry:
        telemetry.add_body("probe")
        for k in range(n):
            t = k / 10
            angle = 2 * math.pi * t / 5554.0
            position = [6.793e6 * math.cos(angle), 6.793e6 * math.sin(angle), 0.0]
            telemetry.state("probe", {
                "t": t, "position": position, "velocity": [0.0, 7660.0, 0.0],
                "attitude": [1.0, 0.0, 0.0, 0.0], "body_rates": [0.0, 0.0, 0.0],
                "latitude_deg": 0.0, "longitude_deg": math.degrees(angle) % 360 - 180,
                "altitude": 415e3, "speed": 7660.0, "orbit": {"eccentricity": 0.0}})
            if k % 6000 == 0:
                telemetry.event(t, "probe", "mark", {"k": k})
                telemetry.log(t, "probe", f"line {k}")
    return n


def test_replay_summary_of_a_one_hour_flight(tmp_path):
    path = tmp_path / "hour.mcap"
    n = _one_hour_file(path)
    t_summary, run = best_of(3, lambda: read_run(path))

    def open_summary():
        with open(path, "rb") as stream:
            return make_reader(stream).get_summary()

    t_open, summary = best_of(3, open_summary)
    total = summary.statistics.message_count
    print(f"\nreplay summary of a one-hour 10 Hz MCAP ({path.stat().st_size / 1e6:.1f} MB, "
          f"{total} messages): {t_summary * 1e3:.0f} ms (target < 1000 ms); opening the file's "
          f"summary section alone: {t_open * 1e3:.1f} ms (ratio {t_summary / t_open:.1f})")
    assert run.problem is None and run.counts["/probe/state"] == n
    assert sum(run.counts.values()) == total and len(run.events) == 7
    assert run.final["probe"]["t"] == 3600.0
