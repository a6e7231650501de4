"""The Level 3 plots on a study of dp_vessel every 90 deg whose runs are made up (known tracks, no
simulation): one fixed scale per plot, tracks beyond it marked and their distance stated, titles
and legends clear of the panels, the quantiles and intervals of the seeds, the transients, and
the criteria and "Not verified by DNV" in every caption."""

import math

import numpy as np
import pytest
from conftest import DATA, ROOT

from allocator_pkg.capability.report.plotting import pyplot
from allocator_pkg.dp.capability_result import INTACT
from allocator_pkg.dp.level3.case import Criteria, excursions
from allocator_pkg.dp.level3.study import Level3Inputs, level3_result, prepare, published
from allocator_pkg.dp.report.level3_plots import (
    FOOTPRINT_VIEW,
    TRANSIENT_VIEW,
    footprints_figure,
    quantiles_figure,
    representative,
    transients_figure,
)

CRITERIA = Criteria(2.0, 3.0, settle=10.0, duration=50.0, seeds=3, quantile=0.9, post_failure_position_limit=3.0,
                    post_failure_window=20.0, resamples=500)
pytestmark = pytest.mark.slow
FAR = 400.0
"""[m] how far the runs of switchboard_a at 90 deg go from condition 2 up."""


def made_up_run(case, criteria):
    """A run of 60 s every 1 s: a circle about the set-point of radius 0.4 m x number x (1 + 0.3
    seed), a bump to 1.5 times it for 10 s after a group's failure, and switchboard_a at 90 deg
    from condition 2 drifting off to :data:`FAR` m."""
    time = np.arange(0.0, 60.0, 1.0)
    radius = np.full(time.shape, 0.4 * case.number * (1.0 + 0.3 * case.seed))
    if case.group != INTACT:
        radius[(time >= 10.0) & (time < 20.0)] *= 1.5
    if (case.heading_deg, case.group) == (90.0, "switchboard_a") and case.number >= 2:
        radius = np.linspace(0.1, FAR, time.size)
    angle = 0.1 * time + math.radians(case.heading_deg)
    track = tuple(zip((radius * np.cos(angle)).tolist(), (radius * np.sin(angle)).tolist()))
    return excursions(case, criteria, time, radius, 0.2 * radius, track)


@pytest.fixture(scope="module")
def made_up():
    inputs = Level3Inputs(ROOT / "config/dp_vessel.yaml", ROOT / "config/particulars/dp_vessel.yaml",
                          site=DATA / "sites" / "level3_site.yaml", heading_step=90.0, criteria=CRITERIA)
    prepared = prepare(inputs)
    finished = {}
    while not prepared.search.done(finished):
        finished.update((case.key, made_up_run(case, CRITERIA)) for case in prepared.search.pending(finished))
    return prepared, level3_result(prepared, finished, published(prepared)), finished


def inside(figure, text) -> bool:
    box = text.get_window_extent(figure.canvas.get_renderer())
    frame = figure.bbox
    return frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1


def clear_of(figure, legend, panels) -> bool:
    box = legend.get_window_extent(figure.canvas.get_renderer())
    return not any(box.overlaps(axes.get_window_extent()) for axes in panels)


def check_caption(figure):
    title = figure._suptitle.get_text().replace("\n", " ")
    assert CRITERIA.short() in title and "Not verified by DNV." in title
    assert inside(figure, figure._suptitle)


def test_the_shown_run_is_the_seed_nearest_the_quantile(made_up):
    prepared, _, finished = made_up
    results = prepared.search.seed_results((0.0, INTACT), 1, finished)
    target = np.quantile([r.max_position for r in results], 0.9)
    nearest = min(results, key=lambda r: abs(r.max_position - target))
    assert representative(results, CRITERIA) is nearest and nearest.case.seed == 2


def test_the_footprints_share_one_scale_and_mark_how_far_a_track_went(made_up):
    prepared, result, finished = made_up
    figure = footprints_figure(prepared, result, finished, "dp_vessel")
    figure.draw_without_rendering()
    panels = [axes for axes in figure.axes if axes.get_title()]
    view = FOOTPRINT_VIEW * CRITERIA.position_limit
    assert [axes.get_title().split("\n")[0] for axes in panels] == ["0 deg", "90 deg", "180 deg", "270 deg"]
    for axes, heading in zip(panels, (0.0, 90.0, 180.0, 270.0)):
        assert axes.get_xlim() == pytest.approx((-view, view)) and axes.get_ylim() == pytest.approx((-view, view))
        numbers = {case: prepared.search.outcome((heading, case), finished).number for case in prepared.search.cases}
        assert axes.get_title().replace("\n", " ").endswith(", ".join(f"{c} {n}" for c, n in numbers.items()))
        beyond = []
        for case, number in numbers.items():
            for shown in (number, number + 1):
                results = prepared.search.seed_results((heading, case), shown, finished)
                if results:
                    track = np.array(representative(results, CRITERIA).track)
                    farthest = float(np.max(np.hypot(track[:, 0], track[:, 1])))
                    if np.max(np.abs(track)) > view:
                        beyond.append(f"{case} {shown}: {farthest:.3g} m")
        texts = [text.get_text() for text in axes.texts]
        assert texts == (["off view:\n" + "\n".join(beyond)] if beyond else [])
        edge = [line for line in axes.get_lines() if line.get_marker() == ">"]
        assert len(edge) == len(beyond)
        for line in edge:
            assert max(abs(line.get_xdata()[0]), abs(line.get_ydata()[0])) == pytest.approx(view)
        assert inside(figure, axes.title)
    assert any(f"switchboard_a 2: {FAR:.3g} m" in text.get_text() for text in panels[1].texts)
    assert clear_of(figure, figure.legends[0], panels)
    check_caption(figure)
    pyplot().close(figure)


def test_the_quantiles_are_the_seeds_with_their_intervals(made_up):
    prepared, result, finished = made_up
    figure = quantiles_figure(prepared, result, finished, "dp_vessel")
    figure.draw_without_rendering()
    cases = prepared.search.cases
    position_panels = figure.axes[:len(cases)]                   # the first row
    for axes, case in zip(position_panels, cases):
        assert axes.get_title() == case
        dots = next(line for line in axes.get_lines() if line.get_marker() == "o")
        for heading, value in zip(dots.get_xdata(), dots.get_ydata()):
            number = prepared.search.outcome((heading, case), finished).number
            seeds = [finished[(heading, number, case, s)].steady_position for s in range(3)]
            assert value == pytest.approx(np.quantile(seeds, 0.9))
        top = 2.0 * (CRITERIA.position_limit if case == INTACT else CRITERIA.post_failure_position_limit)
        assert axes.get_ylim() == (0.0, top)
    failed = next(line for line in position_panels[1].get_lines() if line.get_marker() == "s")
    assert list(failed.get_ydata()) == [6.0] and [t.get_text() for t in position_panels[1].texts] == [f"{FAR:.3g}"]
    assert clear_of(figure, figure.legends[0], figure.axes)
    check_caption(figure)
    pyplot().close(figure)


def test_the_transients_show_each_group_on_one_scale_with_the_post_failure_limit(made_up):
    prepared, result, finished = made_up
    figure = transients_figure(prepared, result, finished, "dp_vessel")
    figure.draw_without_rendering()
    groups = [case for case in prepared.search.cases if case != INTACT]
    panels = [axes for axes in figure.axes if axes.get_title().startswith("loss of")]
    assert [axes.get_title() for axes in panels] == [f"loss of {g}, at each heading's number" for g in groups]
    top = TRANSIENT_VIEW * max(CRITERIA.position_limit, CRITERIA.post_failure_position_limit)
    for axes, group in zip(panels, groups):
        assert axes.get_ylim() == pytest.approx((0.0, top))
        runs = [line for line in axes.get_lines() if line.get_marker() in ("None", "", None)
                and len(line.get_xdata()) == 60]
        shown = [h for h in prepared.search.headings if prepared.search.outcome((h, group), finished).number >= 1]
        assert len(runs) == len(shown)
        for line in runs:
            assert line.get_xdata()[0] == pytest.approx(-CRITERIA.settle)
        limits = [c for c in axes.collections if len(c.get_segments()) == 1]
        segments = sorted(tuple(map(tuple, c.get_segments()[0])) for c in limits)
        assert segments == [((0.0, 3.0), (20.0, 3.0)), ((20.0, 2.0), (50.0, 2.0))]
    assert clear_of(figure, figure.legends[0], panels)
    check_caption(figure)
    pyplot().close(figure)
