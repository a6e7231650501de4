"""The polar plots of a DNV-ST-0111 Level 1 report ([2.4], App. A.3.1): capability number or
limiting wind speed [m/s] per heading, 0 deg (environment from ahead) at the top, clockwise.

:func:`polar_plot` draws the given cases on one figure with the vessel's outline in the middle (the
hull from Lpp and B, bow up, starboard right; each thruster at its position, a failed one as a
cross) and, on the combined plot (Figure A-1: intact and worst single failure), a marker per
heading in the colour of the group whose loss is worst there.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...capability.report.plotting import pyplot
from ..capability_result import INTACT, NOT_YET, NOT_YET_L2, WORST, CapabilityResult
from ..level1 import Level1
from .tables import groups_of, worst_groups

FOOTERS = {
    1: f"Per DNV-ST-0111 Level 1: loads, thrust, ventilation, [3.11.3] zones, [3.11.4]-[3.11.5] losses, [3.10] "
       f"rudders, power per source.\nNot yet: {NOT_YET}.\n"
       "Unclear clauses read as the report says. Not verified by DNV.",
    2: "DNV-ST-0111 Level 2 as read here (no Level 2 text in the transcription used): the vessel's coefficients, "
       f"thrust limits, sectors and site where given.\nNot yet: {NOT_YET_L2}.\nNot verified by DNV.",
    3: "DNV-ST-0111 Level 3 as read here (no Level 3 text in the transcription used): seeded closed-loop time-domain "
       "runs, conditions rising to the first that fails;\ncriteria and durations this package's defaults (in the "
       "caption). Not verified by DNV.",
}
CASE_STYLE = {INTACT: dict(color="tab:blue", linewidth=2.4), WORST: dict(color="tab:red", linewidth=1.8,
                                                                         linestyle="--")}
GROUP_COLOURS = ("tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:pink", "tab:olive", "tab:cyan")


@dataclass(frozen=True)
class Outline:
    """The vessel seen from above in the standard's frame: hull length and breadth [m], thruster
    positions (x forward of Lpp/2, y to starboard) by name."""

    lpp: float
    beam: float
    thrusters: dict[str, tuple[float, float]]

    @classmethod
    def of(cls, analysis: Level1) -> Outline:
        frame = analysis.particulars.frame
        return cls(analysis.particulars.hull.lpp, analysis.particulars.hull.beam,
                   {a.name: (frame.standard_x(a.position[0]), a.position[1]) for a in analysis.vehicle.actuators})

    def hull(self) -> tuple[np.ndarray, np.ndarray]:
        """(starboard, forward) of a ship-shaped waterline: parallel sides aft, a pointed bow."""
        half_l, half_b = 0.5 * self.lpp, 0.5 * self.beam
        shoulder = 0.2 * self.lpp
        side = np.array([(-half_l, 0.85 * half_b), (-0.4 * half_l, half_b), (shoulder, half_b),
                         (0.75 * half_l, 0.6 * half_b), (half_l, 0.0)])
        points = np.vstack([side, side[-2::-1] * [1.0, -1.0], side[:1]])
        return points[:, 1], points[:, 0]


def group_colours(result: CapabilityResult) -> dict[str, str]:
    return {g: GROUP_COLOURS[k % len(GROUP_COLOURS)] for k, g in enumerate(groups_of(result))}


def polar_plot(path: Path, *args, **kwargs) -> None:
    """:func:`polar_figure` written to ``path``."""
    figure = polar_figure(*args, **kwargs)
    figure.savefig(path, dpi=100)
    plt = pyplot()

    plt.close(figure)


def polar_figure(result: CapabilityResult, title: str, caption: str, wind: bool, cases: list[str], outline: Outline,
                 failed: tuple[str, ...] = (), mark_worst: bool = False):
    """One polar figure of ``cases`` (keys of the result); ``caption`` says what it shows."""
    plt = pyplot()

    values = result.wind_limits if wind else result.numbers
    colours = group_colours(result)
    figure = plt.figure(figsize=(8.0, 8.4))
    axes = figure.add_subplot(projection="polar")
    angles = np.radians(np.append(result.headings_deg, result.headings_deg[0]))
    for case in cases:
        style = CASE_STYLE.get(case, dict(color=colours.get(case, "k"), linewidth=1.8))
        closed = np.append(values[case], values[case][0])
        label = case if case in (INTACT, WORST) else f"loss of {case}"
        axes.plot(angles, closed, label=label, **style)
        axes.fill(angles, closed, alpha=0.10, color=style["color"])
    if mark_worst:
        worst = np.array(worst_groups(result))
        for group, colour in colours.items():
            where = worst == group
            if np.any(where):
                axes.scatter(np.radians(result.headings_deg[where]), values[WORST][where], s=28, color=colour,
                             zorder=5, label=f"worst here: {group}")
    axes.set_theta_zero_location("N")
    axes.set_theta_direction(-1)
    top = len(result.conditions) - 1
    if wind:
        axes.set_ylim(0.0, result.conditions[top].wind)
        quantity = "limiting wind speed [m/s]"
    else:
        axes.set_ylim(0, top)
        axes.set_yticks(range(top + 1))
        quantity = "DP capability number"
    axes.set_rlabel_position(22.5)
    axes.set_title(f"{title}: {result.summary_line()}\n{caption}: {quantity}\nenvironment from heading "
                   "(0 = head on, 90 = from starboard)", pad=22, fontsize=11)
    draw_outline(axes, outline, failed)
    figure.tight_layout(rect=(0.0, 0.12, 1.0, 1.0))
    figure.legend(loc="lower center", bbox_to_anchor=(0.5, 0.065), ncol=4, fontsize=8.5, frameon=False)
    figure.text(0.5, 0.01, FOOTERS[result.level], ha="center", va="bottom", fontsize=7, wrap=True)
    return figure


def comparison_plot(path: Path, level1: CapabilityResult, level2: CapabilityResult, title: str, wind: bool,
                    outline: Outline) -> None:
    """Level 1 and Level 2, intact and worst single failure, on one polar figure."""
    plt = pyplot()

    figure = polar_figure(level2, title, f"Level 1 ({level1.summary_line()}) against Level 2", wind,
                          [INTACT, WORST], outline)
    axes = figure.axes[0]
    angles = np.radians(np.append(level1.headings_deg, level1.headings_deg[0]))
    values = level1.wind_limits if wind else level1.numbers
    for line in axes.get_lines():
        line.set_label(f"Level 2 {line.get_label()}")
    for case, colour in ((INTACT, "tab:cyan"), (WORST, "tab:orange")):
        axes.plot(angles, np.append(values[case], values[case][0]), color=colour, linewidth=1.4, linestyle=":",
                  label=f"Level 1 {case}")
    tops = (level1.conditions[-1], level2.conditions[-1])
    axes.set_ylim(0.0, max(c.wind for c in tops) if wind else max(len(level1.conditions), len(level2.conditions)) - 1)
    for legend in figure.legends:
        legend.remove()
    figure.legend(loc="lower center", bbox_to_anchor=(0.5, 0.065), ncol=4, fontsize=8.5, frameon=False)
    figure.savefig(path, dpi=100)
    plt.close(figure)


def draw_outline(axes, outline: Outline, failed: tuple[str, ...]) -> None:
    """The vessel in an inset at the centre of the polar axes, to scale, bow up."""
    inset = axes.inset_axes((0.41, 0.36, 0.18, 0.28))
    inset.set_label("vessel outline")
    starboard, forward = outline.hull()
    inset.fill(starboard, forward, color="0.85", alpha=0.6, edgecolor="0.3", linewidth=1.0)
    for name, (x, y) in outline.thrusters.items():
        if name in failed:
            inset.plot(y, x, marker="x", color="tab:red", markersize=7, markeredgewidth=2.0, linestyle="none")
        else:
            inset.plot(y, x, marker="o", color="0.15", markersize=4.5, linestyle="none")
    reach = 0.55 * outline.lpp
    inset.set_xlim(-reach, reach)
    inset.set_ylim(-reach, reach)
    inset.set_aspect("equal")
    inset.axis("off")
