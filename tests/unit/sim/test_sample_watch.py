"""The sample watch's coast rule and flight figures, checked against the rule stated sample by
sample (the module's text, written out here one sample at a time): interleaved blocks of
several bodies, written in blocks, give the same samples in the same order, hold back the same
last samples and give the same figures as the samples handed over one by one."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rocketsim.constants import G0
from rocketsim.sim.sample_watch import IN_AIR_Q, SETTLE_BLOCKS, SampleWatch
from rocketsim.stepping.sample_figures import (N_SAMPLE_RIGID, SAMPLE_DYNAMIC_PRESSURE, SAMPLE_ENGINES_RUNNING,
                                               SAMPLE_HEIGHT_AGL, SAMPLE_MACH, SAMPLE_SENSED, SAMPLE_SURFACE_SPEED)
from rocketsim.telemetry.sample_plans import interleaved_samples

H, EVERY, COAST_EVERY = 0.01, 10, 100      # s a step, steps between samples, steps between a coast's samples
WIDTH = {"vehicle": N_SAMPLE_RIGID + 8, "part": N_SAMPLE_RIGID}


def fields(values, integer):
    return {}


class Kept:
    """A sink keeping the samples written to it, one at a time, in order."""

    def __init__(self):
        self.written = []

    def sample(self, body, values, fields, leaving=False):
        self.written.append((body, values.tobytes(), leaving))

    def sample_rows(self, body, rows, fields):
        for values in rows:
            self.sample(body, values, fields)

    def sample_interleaved(self, blocks):
        for body, values, shape in interleaved_samples(blocks):
            self.sample(body, values, shape)

    def event(self, t, body, name, figures):
        pass


def rows_of(body: str, steps: list[int], draw) -> np.ndarray:
    """Samples of ``body`` at ``steps``: in the air or not, engines running or not, heights."""
    rows = np.full((len(steps), WIDTH[body]), 7.0)
    rows[:, -2] = np.array(steps) * H
    rows[:, SAMPLE_DYNAMIC_PRESSURE] = draw(st.lists(st.sampled_from([0.0, 0.5, 1.0, 5e4, math.nan]),
                                                     min_size=len(steps), max_size=len(steps)))
    rows[:, SAMPLE_HEIGHT_AGL] = draw(st.lists(st.sampled_from([0.0, 10.0, 250.0, 250.0, 9e4]),
                                               min_size=len(steps), max_size=len(steps)))
    for column in (SAMPLE_SURFACE_SPEED, SAMPLE_MACH, SAMPLE_SENSED):
        rows[:, column] = draw(st.lists(st.floats(0.0, 1e4), min_size=len(steps), max_size=len(steps)))
    if body == "vehicle":
        rows[:, SAMPLE_ENGINES_RUNNING] = draw(st.lists(st.sampled_from([0.0, 0.0, 1.0, 9.0]),
                                                        min_size=len(steps), max_size=len(steps)))
    return rows


@st.composite
def flights(draw):
    """Calls of interleaved blocks of two bodies (a row per sample step, from a step that may be
    off the sample steps), each call's blocks at later steps than the last's."""
    calls, step = [], 0
    for _ in range(draw(st.integers(1, 6))):
        blocks = []
        for rank, body in enumerate(draw(st.sampled_from([["vehicle"], ["part"], ["vehicle", "part"]]))):
            first = step + draw(st.sampled_from([0, 0, 3]))
            n = draw(st.integers(0, 25))
            steps = [first + EVERY * j for j in range(n)]
            blocks.append((body, rows_of(body, steps, draw), fields, first, EVERY, rank))
        calls.append(blocks)
        step = max([step] + [b[3] + EVERY * len(b[1]) for b in blocks])
    return calls


def kept_by_the_rule(values: np.ndarray) -> bool:
    """The coast rule of one sample (see the module of the sample watch)."""
    step = round(values[-2] / H)
    coasting = not values[SAMPLE_DYNAMIC_PRESSURE] >= IN_AIR_Q
    if len(values) > N_SAMPLE_RIGID:
        coasting = coasting and values[SAMPLE_ENGINES_RUNNING] == 0
    return not coasting or step % EVERY != 0 or step % COAST_EVERY == 0


@settings(max_examples=60, deadline=None)
@given(flights())
def test_interleaved_blocks_write_what_the_rule_writes_sample_by_sample(calls):
    blocks_sink, one_sink = Kept(), Kept()
    blocks_watch = SampleWatch(blocks_sink, H, EVERY, COAST_EVERY)
    one_watch = SampleWatch(one_sink, H, EVERY, COAST_EVERY)
    expected, held = [], {}
    for blocks in calls:
        blocks_watch.sample_interleaved(blocks)
        for body, values, _ in interleaved_samples(blocks):
            one_watch.sample(body, values, fields)
            if kept_by_the_rule(values):
                expected.append((body, values.tobytes(), False))
                held.pop(body, None)
            else:
                held[body] = values
    assert blocks_sink.written == expected
    assert one_sink.written == expected
    blocks_watch.finish()
    one_watch.finish()
    last = [(body, values.tobytes(), False) for body, values in held.items()]
    assert blocks_sink.written == expected + last
    assert one_sink.written == expected + last
    for body in WIDTH:
        assert blocks_watch.figures(body) == one_watch.figures(body)


def test_the_figures_of_many_blocks_are_those_of_their_samples_in_flight():
    rng = np.random.default_rng(7)
    watch = SampleWatch(Kept(), H, EVERY, COAST_EVERY)
    rows = np.zeros((5 * SETTLE_BLOCKS + 3, WIDTH["vehicle"]))
    rows[:, -2] = np.arange(len(rows)) * EVERY * H
    rows[:, SAMPLE_HEIGHT_AGL] = rng.uniform(0.0, 1e3, len(rows))
    rows[[40, 90, 200, 300], SAMPLE_HEIGHT_AGL] = 2e3           # the highest, four times: the first is the apogee
    rows[:, SAMPLE_SURFACE_SPEED] = rng.uniform(0.0, 300.0, len(rows))
    rows[:, SAMPLE_MACH] = rng.uniform(0.0, 3.0, len(rows))
    rows[:, SAMPLE_DYNAMIC_PRESSURE] = rng.choice([0.0, 0.5, 2e4, 3e4], len(rows))
    rows[:, SAMPLE_SENSED] = rng.uniform(0.0, 40.0, len(rows))
    landing = 250
    rows[landing + 1:, SAMPLE_SURFACE_SPEED] = 1e6            # after the landing: not flight figures
    for k in range(0, landing + 1, 2):                        # blocks of two samples
        watch.sample_rows("vehicle", rows[k:min(k + 2, landing + 1)], fields)
    watch.event(rows[landing, -2], "vehicle", "touchdown", {})
    for k in range(landing + 1, len(rows)):
        watch.sample("vehicle", rows[k], fields)
    flown = rows[:landing]                                    # the landing's own sample left out
    air = flown[:, SAMPLE_DYNAMIC_PRESSURE] >= IN_AIR_Q
    figures = watch.figures("vehicle")
    assert figures["apogee_height_agl_m"] == 2e3 and figures["apogee_time_s"] == flown[40, -2]
    assert figures["max_surface_speed_m_s"] == flown[:, SAMPLE_SURFACE_SPEED].max()
    assert figures["max_mach"] == flown[air, SAMPLE_MACH].max()
    assert figures["max_dynamic_pressure_Pa"] == 3e4
    assert figures["max_sensed_acceleration_g"] == flown[:, SAMPLE_SENSED].max() / G0


def test_a_body_split_off_starts_with_its_parents_figures_so_far():
    watch = SampleWatch(Kept(), H, EVERY, None)
    rows = np.zeros((3, WIDTH["vehicle"]))
    rows[:, -2] = [0.0, 0.1, 0.2]
    rows[:, SAMPLE_HEIGHT_AGL] = [5.0, 80.0, 60.0]
    watch.sample_rows("vehicle", rows, fields)
    watch.inherit("booster", "vehicle")
    later = rows[2:].copy()
    later[:, -2], later[:, SAMPLE_HEIGHT_AGL] = 0.3, 500.0
    watch.sample_rows("vehicle", later, fields)
    assert watch.figures("booster")["apogee_height_agl_m"] == 80.0
    assert watch.figures("vehicle")["apogee_height_agl_m"] == 500.0
