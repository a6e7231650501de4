"""The result of a DNV-ST-0111 DP capability analysis at Level 1, 2 or 3, and what each level's
outputs say about themselves (:data:`SCOPES`).

A :class:`CapabilityResult` is complete before anything is written: the capability number and
the limiting wind speed per heading for each case (``intact``, each redundancy group by name and
``worst single failure``, per heading the lowest over the groups [2.4.7]), the notes on what the
numbers rest on, the condition of each number (Table 2-1 or a site's), at Levels 1 and 2 the
allocation behind Tables A-8 to A-10 per case and heading (:class:`Allocation`), and the results of
the lower levels of the same vessel it is drawn against (a Level 2 result its Level 1; Level 3 its
Levels 1 and 2). :meth:`CapabilityResult.summary` gives DP capability-L<level>(A, B, C, D) [2.4].
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .standard.weather import WEATHER_CONDITIONS, WeatherCondition

INTACT = "intact"
WORST = "worst single failure"
BOW_SECTOR_DEG = 30.0
"""A and C are the minima within this many degrees of the bow."""
PER_STANDARD = ("loads [3.5]-[3.7] times the dynamic factor 1.25 [3.2.2]; nominal thrust [3.9.2] times beta_misc "
                "[3.9.3] and the ventilation loss [3.9.4]; forbidden zones [3.11.3] among the working thrusters; the "
                "thrust loss flushing a dead thruster [3.11.4] and a skeg [3.11.5] by thrust direction [3.11.6]; "
                "rudders behind shaft lines [3.10]; the power balance per source [3.12.3]-[3.12.5] jointly with the "
                "thrust: each source's capacity less the 10 % reserve against the power its thrusters draw at the "
                "thrust the balance needs")
NOT_YET = "no clause of [3.2]-[3.12] that the transcription gives"
READINGS = ("g 9.81 m/s^2 ([3.7] fixes none); a thruster that loses the feed share s keeps (1 - s) P_B ([3.12], "
            "Table A-5); the power at part thrust P_B r^(3/2), [3.9.2] turned around ([3.12] gives none); the "
            "second range of B in [3.9.4] read as the union of [-pi, -pi/2] and [pi/2, pi]; T_nominal of [3.9.4] "
            "in N; the columns of Tables A-9 and A-10 (the transcription names their content, the power per thruster "
            "and per switchboard with its reserve, not their columns)")
"""Where the text cannot be read as it stands, and how it is read here."""
SCOPE_L1 = (f"Per DNV-ST-0111 (Dec 2021) Level 1: {PER_STANDARD}. Not yet: {NOT_YET}. Read where the text is "
            f"unclear: {READINGS}. Not verified by DNV.")
"""What every Level 1 output says about itself."""
OWN_DATA = ("wind and current loads from the particulars' coefficient tables over heading where given ([3.5], [3.6] "
            "where not); each thruster's thrust from the vehicle file's thrust limits (no [3.9.3]/[3.9.4]/[3.11.4]/"
            "[3.11.5] loss; a lost feed share s leaves (1 - s)^(2/3) of it), times the particulars' thrust-loss "
            "tables over the thrust direction and over the current speed where given (the notes list them); "
            "the vehicle file's forbidden sectors "
            "(lifted with the thruster they protect); a site environment in place of Table 2-1 where given")
KEPT = ("wave drift [3.7], the dynamic factor 1.25 [3.2.2], rudders behind shaft lines [3.10], the power balance "
        "per source [3.12], the redundancy groups")
NOT_YET_L2 = f"the vessel's wave drift data; {NOT_YET}"
SCOPE_L2 = (f"DNV-ST-0111 (Dec 2021) Level 2 as read here (the transcription used has no Level 2 text): the Level 1 "
            f"balance with the vessel's own data: {OWN_DATA}. Kept from Level 1: {KEPT}. Not yet: {NOT_YET_L2}. "
            "Not verified by DNV.")
"""What every Level 2 output says about itself."""
SCOPE_L3 = ("DNV-ST-0111 (Dec 2021) Level 3 as read here (the transcription used has no Level 3 text): seeded "
            "in-process closed-loop time-domain runs of the vessel with this package's allocator and DP system (a "
            "passive observer on noisy position and heading, the controller on its estimate, wind feed-forward), "
            "thrusters with the static analysis' losses, a failure a trip; the mean wind load [3.5] and wave drift "
            "[3.7] of the standard with gusts from a wind spectrum, a JONSWAP sea's slowly varying drift (Newman) "
            "and wave motion, the current through the simulation's hull model; wind, current and waves of Table 2-1 "
            "(or the Level 2 site's) from each heading; a redundancy group failed after settling on station; "
            "conditions rising per [2.4.4] to the first that fails, each decided over seeds by a stated quantile; a "
            "condition the static Level 2 balance fails is not simulated. Not verified by DNV.")
"""What every Level 3 output says about itself."""
SCOPES = {1: SCOPE_L1, 2: SCOPE_L2, 3: SCOPE_L3}


@dataclass(frozen=True)
class ThrusterUse:
    """One thruster in one balance: thrust [N] (signed for a fixed thruster), its angle [deg, body
    frame] and the effective thrust available in that direction [N]."""

    name: str
    thrust: float
    angle_deg: float
    available: float

    @property
    def utilisation(self) -> float:
        """Table A-8's utilisation: the thrust over what the thruster can give that way."""
        return abs(self.thrust) / self.available if self.available > 0.0 else 0.0


class Allocation(NamedTuple):
    """The allocation Tables A-8 to A-10 report for one case and heading: at the heading's
    capability number, each working thruster's :class:`ThrusterUse`."""

    case: str
    heading_deg: float
    number: int
    uses: tuple[ThrusterUse, ...]


@dataclass(frozen=True)
class CapabilityResult:
    """Capability numbers and limiting wind speeds per heading for each case: ``intact``, each
    redundancy group by name, and ``worst single failure`` (per heading the lowest over the groups)."""

    headings_deg: np.ndarray
    numbers: dict[str, np.ndarray]
    wind_limits: dict[str, np.ndarray]
    notes: tuple[str, ...]
    level: int = 1
    """The standard's level of the analysis: 1, 2 (with the vessel's own data) or 3 (time domain)."""
    conditions: tuple[WeatherCondition, ...] = WEATHER_CONDITIONS
    """The condition of each number (Table 2-1, or a site's at Levels 2 and 3)."""
    allocations: tuple[Allocation, ...] = ()
    """Per case (intact, then each group) and heading the allocation at its number (Levels 1 and 2)."""
    lower: tuple[CapabilityResult, ...] = ()
    """The results of the lower levels of the same vessel, lowest first (drawn against this one)."""

    @property
    def scope(self) -> str:
        """What is per the standard and what is not, for every output of the level."""
        return SCOPES[self.level]

    def summary(self) -> tuple[int, int, int, int]:
        """(A, B, C, D): intact minimum within +-30 deg of the bow and over every heading, the
        same for the worst single failure."""
        return capability_summary(self.headings_deg, self.numbers[INTACT], self.numbers[WORST])

    def summary_line(self) -> str:
        return f"DP capability-L{self.level}" + "({}, {}, {}, {})".format(*self.summary())

    def rows(self) -> list[tuple[str, float, int, float]]:
        """(case, heading_deg, capability_number, wind_speed_limit) for every case and heading."""
        return [(case, float(heading), int(self.numbers[case][k]), float(self.wind_limits[case][k]))
                for case in self.numbers for k, heading in enumerate(self.headings_deg)]


def capability_summary(headings_deg: np.ndarray, intact: np.ndarray,
                       worst: np.ndarray) -> tuple[int, int, int, int]:
    """(A, B, C, D) of the numbers per heading [2.4]."""
    off_bow = np.abs((np.asarray(headings_deg) + 180.0) % 360.0 - 180.0)
    bow = off_bow <= BOW_SECTOR_DEG + 1e-9
    return (int(np.min(intact[bow])), int(np.min(intact)), int(np.min(worst[bow])), int(np.min(worst)))
