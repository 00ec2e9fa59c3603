"""The detected walking bouts of a track, one row each (decision L124, docs/decisions/localization.md): what
``track`` writes as ``OUT/bouts.csv`` for the foot and the lower-back pipelines alike.

By default (gap ``rhythm``) a bout is L104's walking bout (:mod:`pdrlearn.track.clinical`): the rows of
``steps.csv`` between two pauses, a pause being a row-to-row interval at least ``break_s`` longer than the walk's
median interval (the walker's own rhythm; a turn across the interval takes its time first, L119). ``break_s``
defaults to L104's :data:`~pdrlearn.track.clinical.PAUSE_MIN_S` (1 s), so the default table has
``n_walking_bouts`` rows. A bout with fewer than ``min_strides`` strides is left out of the table (its steps stay
in the track's totals); default 0 (every bout, as L104 counts them).

Decision L163: that rhythm rule with ``break_s=3`` is NOT mobgap's rule - its effective break is the median step
interval plus 3 s plus angle / 20 deg/s for a turn across the gap, so a Mobilise-D trial found bouts spanning
4.9-6.5 s without a contact. ``--bout-rule mobgap`` (:data:`BOUT_PRESETS`) is the literal rule: gap ``contact``, a
new bout when two consecutive initial contacts are more than 3 s apart, at least 4 strides (decision L676: on a foot
track, whose rows are one foot's contacts, the same-foot gap less one step time, the other foot's unseen contact).
Every row says its ``longest_contact_gap_s``, so a bout spanning a longer gap than the break is visible under either
rule.

Decision L269: a foot-data gap (L67's gap row) longer than ``break_s`` ends a bout under either rule, the gap row
in neither bout; ``data_gap_s`` sums the shorter gaps a bout holds (summary.json's ``time_no_data_s``, L275, is
the session's time in data gaps).
"""

from __future__ import annotations

import warnings
from dataclasses import asdict, dataclass

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.track.clinical import (
    CV_BOUT_MIN_STRIDES,
    PAUSE_MIN_S,
    TURN_COUNT_MIN_DEG,
    bout_rows,
    cv_pct,
    data_gap_lengths,
    is_foot_table,
    split_at_data_gaps,
    steady_rows,
    steady_stride_lengths,
    turn_filled,
    turn_rows,
)
from pdrlearn.track.turn_gaps import TurnGaps
from pdrlearn.waist.gait_quality import QUALITY_COLUMNS

#: bouts.csv's columns, in order (docs/columns.md; decision L165: ``session`` / ``subject`` first, the join key;
#: C100: and ``visit``)
BOUT_COLUMNS = ("session", "subject", "visit", "bout", "start_s", "end_s", "duration_s", "n_steps", "n_strides",
                "distance_m", "speed_mps", "stride_length_m", "contact_span_s", "n_step_intervals", "cadence_spm",
                "longest_contact_gap_s", "data_gap_s", "n_turns", "direction", "backward_fraction",
                "n_backward_strides", "n_side_strides",  # decision L581
                "altitude_change_m",
                "altitude_change_before_m", "floors_up", "floors_down",  # decision L450
                "ascent_m", "descent_m",  # decision L467
                "gait_out_of_range", "n_cv_strides", "stride_time_cv_pct",
                "stride_length_cv_pct", *QUALITY_COLUMNS)  # decision W350: a lower-back track's gait quality

#: decision E98: bouts.csv's renamed columns, old name -> new (speeds are ``_mps`` as everywhere else). The old name
#: stays readable: a :class:`BoutsTable` answers it with a FutureWarning, and the CSVs keep it as a last column
#: (:func:`csv_table`) until a later release drops it
RENAMED_BOUT_COLUMNS = {"speed_m_s": "speed_mps"}


def _renamed(key, columns):
    """Decision E98: ``key`` with a renamed column's old name replaced by the new one (one FutureWarning each)."""
    if isinstance(key, str) and key in RENAMED_BOUT_COLUMNS and key not in columns:
        new = RENAMED_BOUT_COLUMNS[key]
        warnings.warn(f"bouts column '{key}' is now '{new}' (decision E98: speeds are _mps); '{key}' will be removed",
                      FutureWarning, stacklevel=3)
        return new
    if isinstance(key, list):
        return [_renamed(k, columns) for k in key]
    return key


class BoutsTable(pd.DataFrame):
    """:func:`detected_bouts`'s table: a DataFrame whose renamed columns (decision E98, :data:`RENAMED_BOUT_COLUMNS`)
    are still readable under their old names, ``table["speed_m_s"]`` or ``table.speed_m_s``, with a FutureWarning."""

    @property
    def _constructor(self):
        return BoutsTable

    def __getitem__(self, key):
        return super().__getitem__(_renamed(key, self.columns))

    def __getattr__(self, name: str):
        if name in RENAMED_BOUT_COLUMNS:
            return self[name]
        return super().__getattr__(name)


def csv_table(table: pd.DataFrame) -> pd.DataFrame:
    """Decision E98: the table as bouts.csv writes it - :data:`BOUT_COLUMNS`, then each renamed column's old name
    (the same values; deprecated, kept so that scripts reading it keep working until a later release)."""
    out = pd.DataFrame(table)
    return out.assign(**{old: out[new] for old, new in RENAMED_BOUT_COLUMNS.items()})


def current_names(table: pd.DataFrame) -> pd.DataFrame:
    """Decision E98: a bouts.csv read back (an older run's, for ``track-all --resume``) with the current names."""
    old = {o: n for o, n in RENAMED_BOUT_COLUMNS.items() if o in table.columns and n not in table.columns}
    return table.rename(columns=old)


#: decision L163: the ways a bout ends - ``rhythm`` (L104/L119: a row-to-row interval at least ``break_s`` beyond
#: the walk's median interval, a turn across it taking its time first) or ``contact`` (mobgap's literal rule: two
#: consecutive initial contacts more than ``break_s`` apart)
GAP_KINDS = ("rhythm", "contact")
#: decision L163: ``--bout-rule`` presets. ``mobgap``: Mobilise-D's walking-bout rule as mobgap 1.2.0 implements it
#: (``mobgap.wba.WbAssembly`` with ``MaxBreakCriteria(max_break_s=3)`` and ``NStridesCriteria(min_strides=4)``; the
#: Mobilise-D consensus of Kluge et al. 2021, PLoS ONE 16(8) e0256541, which mobgap's WBA docs cite - no seed paper
#: holds it): a new bout when the contact gap exceeds 3 s, at least 4 strides
#: decision W495: ``mobgap-indip`` is ``mobgap`` with each lower-back bout from its second contact to its last-but-one
#: (``trim_edges``): on the 9 real mobgap recordings the detected bouts start 0.9 and end 2.1 step intervals beyond
#: INDIP's WBs (medians), which alone fails mobgap's 0.8 overlap on short WBs; an option, not the default (W495)
BOUT_PRESETS = {"pdrlearn": {"gap": "rhythm", "break_s": PAUSE_MIN_S, "min_strides": 0},
                "mobgap": {"gap": "contact", "break_s": 3.0, "min_strides": 4},
                "mobgap-indip": {"gap": "contact", "break_s": 3.0, "min_strides": 4, "trim_edges": True}}


@dataclass(frozen=True)
class BoutRule:
    """Decisions L124, L163: the walking-bout definition. ``break_s``: a break of at least this (s) ends a bout
    (L104's 1 s by default); ``min_strides``: a bout needs at least this many strides (0: every bout); ``gap``: how
    the break is measured (:data:`GAP_KINDS`: beyond the walker's rhythm, or the raw contact-to-contact gap)."""

    break_s: float = PAUSE_MIN_S
    min_strides: int = 0
    gap: str = "rhythm"
    #: decision W495: a lower-back bout (found and kept by the rule above) runs from its second contact to its
    #: last-but-one, its measures from the steps between (:func:`edge_trimmed`)
    trim_edges: bool = False
    #: decisions C180 / C182: under the ``rhythm`` gap an interval a walker's yaw-rate turn of at least this |angle|
    #: (deg) fills ends no bout (:mod:`pdrlearn.track.turn_gaps`); None: off (the default: C180's 90 deg failed on
    #: real daily life, an option); ``--corridor`` sets L383's cone turn, 135 deg (C182, :func:`corridor_rule`)
    turn_fill_min_deg: float | None = None

    def __post_init__(self):
        if not (np.isfinite(self.break_s) and self.break_s > 0):
            raise DataError(f"--bout-break-s {self.break_s:g}: a pause length in s must be a positive number, "
                            f"e.g. {PAUSE_MIN_S:g} (the default) or 3 (Mobilise-D's break)")
        if self.min_strides < 0:
            raise DataError(f"--bout-min-strides {self.min_strides}: give 0 (every bout, the default) or more, "
                            "e.g. 4 (mobgap's Mobilise-D rule)")
        if self.gap not in GAP_KINDS:
            raise DataError(f"bout rule gap {self.gap!r}: give one of {', '.join(GAP_KINDS)}")
        if self.turn_fill_min_deg is not None and not (np.isfinite(self.turn_fill_min_deg)
                                                       and 0 < self.turn_fill_min_deg <= 360):
            raise DataError(f"bout rule turn_fill_min_deg {self.turn_fill_min_deg!r}: give a turn angle in deg "
                            "(0-360], e.g. 135 (a corridor's cone turn, decision C182), or None (off)")

    def record(self) -> dict:
        """The definition as summary.json's ``bout_definition`` (``trim_edges`` only when on, W495;
        ``turn_fill_min_deg`` only when set, C182)."""
        out = asdict(self)
        if not self.trim_edges:
            out.pop("trim_edges")
        if self.turn_fill_min_deg is None:
            out.pop("turn_fill_min_deg")
        return out

    def turn_gaps(self, info: dict | None) -> TurnGaps | None:
        """Decisions C180 / C182: the turns that fill a track's pauses under this rule (``info``: the track's, its
        ``yaw_turns`` and ``transfers``); None when the rule fills none (off, or the ``contact`` gap)."""
        if self.turn_fill_min_deg is None or self.gap != "rhythm":
            return None
        return TurnGaps.of(info, min_deg=self.turn_fill_min_deg)


def corridor_rule(rule: BoutRule | None, corridor_m: float | None) -> BoutRule | None:
    """Decision C182: with ``--corridor`` (``corridor_m`` given) the bout rule whose ``rhythm`` gap a cone turn
    (L383's :data:`~pdrlearn.track.corridor.CONE_TURN_MIN_DEG`) fills; ``rule`` unchanged without a corridor, with
    the ``contact`` gap (mobgap's literal rule) or with a fill angle given."""
    from dataclasses import replace

    from pdrlearn.track.corridor import CONE_TURN_MIN_DEG

    rule = rule or BoutRule()
    if corridor_m is None or rule.gap != "rhythm" or rule.turn_fill_min_deg is not None:
        return rule
    return replace(rule, turn_fill_min_deg=CONE_TURN_MIN_DEG)


def bout_rule(break_s: float | None = None, min_strides: int | None = None, preset: str | None = None) -> BoutRule:
    """The rule of ``--bout-rule`` / ``--bout-break-s`` / ``--bout-min-strides`` (None: the preset's value, the
    preset ``pdrlearn`` by default; decision L163), checked once before any tracking (decision L124; ``track``,
    ``track-all`` and ``run`` read the options with this, decision L130)."""
    name = (preset or "pdrlearn").strip().lower()
    if name not in BOUT_PRESETS:
        raise DataError(f"--bout-rule {preset}: give one of {', '.join(BOUT_PRESETS)} (mobgap: Mobilise-D's rule, "
                        "a new bout when two contacts are more than 3 s apart, at least 4 strides)")
    given = {k: v for k, v in (("break_s", break_s), ("min_strides", min_strides)) if v is not None}
    return BoutRule(**{**BOUT_PRESETS[name], **given})


def cadence_spm(n_step_intervals: float, span_s: float) -> float:
    """Decision L164: THE cadence of pdrlearn's bout tables - steps per minute over the contact span: the
    ``n_step_intervals`` steps between a bout's first and last initial contact (contacts - 1; 2 per stride of a
    tracked foot, L66) in the ``span_s`` seconds between them; NaN without a span. bouts.csv's ``cadence_spm`` and
    subjects.csv's pooled one (:func:`pdrlearn.visits.subject_totals`) both are this."""
    return 60.0 * n_step_intervals / span_s if span_s > 0 else np.nan


#: decision W602: bouts.csv's cadence terms over a lower-back bout's inner steps ("inner", the default) or all
#: its steps (L164's first to last contact, "all"); a foot track's bouts always take all
EDGE_STEPS = ("inner", "all")


def step_terms(ic: np.ndarray, filled: np.ndarray, *, inner: bool) -> tuple[float, int]:
    """L164's cadence terms ``(span_s, n_step_intervals)`` of one bout's contact times ``ic`` (s, in order; NaN: no
    contact): the step intervals between consecutive contacts, less those a walker's turn fills (``filled``, one per
    interval; decision C180) and, with ``inner`` (decision W602), less the bout's first and last interval - the lower
    back reads a bout's first contact late and its closing one early (the edge steps read 0.39-0.46 s where the inner
    ones read 0.51-0.57 s), so its cadence is taken from the second contact to the last-but-one, and the intervals
    either side of a turn-filled one (the edges of the walking stretches the turn joins) are left out too.
    ``(0.0, 0)`` when no interval is left (a bout of fewer than 4 contacts under ``inner``)."""
    step = np.diff(np.asarray(ic, dtype=float))
    gap = np.asarray(filled, dtype=bool)
    keep = np.isfinite(step) & ~gap
    if inner and len(keep):
        keep[0] = keep[-1] = False
        keep &= ~np.r_[gap[1:], False] & ~np.r_[False, gap[:-1]]  # the stretches either side of a turn end there
    return float(step[keep].sum()), int(keep.sum())


def contact_times(st: pd.DataFrame) -> np.ndarray:
    """Each row's initial contact (``event_s``, else - absent or NaN - ``start_s``); the bouts' cut and the freeze
    checks (W395, W397) read a step's time alike."""
    t = st["start_s"].to_numpy(float)
    if "event_s" not in st:
        return t
    ic = st["event_s"].to_numpy(float)
    return np.where(np.isfinite(ic), ic, t)


def contact_gaps(st: pd.DataFrame, break_s: float) -> np.ndarray:
    """Decision L163's ``contact`` gaps of ``st`` (sorted by ``start_s``): the times (s) between consecutive rows'
    contacts. Decision L676: on a foot track the rows are one foot's contacts, and the other foot's contact lies in
    each gap unseen (Mobilise-D's 3 s break is between consecutive contacts of both feet), so there the gap is the
    same-foot gap less one step time - half the median of the same-foot gaps of at most ``break_s`` (the strides
    inside bouts); no such gap: unchanged. The other foot's closing or opening step at a stop is taken to last one
    step time, so the longer part of the gap is what is compared."""
    gaps = np.diff(contact_times(st))
    if not is_foot_table(st):
        return gaps
    walking = gaps[np.isfinite(gaps) & (gaps <= break_s)]
    return gaps - 0.5 * float(np.median(walking)) if len(walking) else gaps


def _contact_bouts(st: pd.DataFrame, break_s: float) -> list[tuple[int, int]]:
    """Decision L163's ``contact`` gap: the rows between two consecutive contacts more than ``break_s`` apart
    (:func:`contact_gaps`; L676: a foot track's gap less the other foot's step)."""
    if not len(st):
        return []
    cuts = [0, *(np.flatnonzero(contact_gaps(st, break_s) > break_s) + 1).tolist(), len(st)]
    return split_at_data_gaps(st, list(zip(cuts[:-1], cuts[1:], strict=True)), break_s)  # decision L269


def bout_ranges(steps: pd.DataFrame, rule: BoutRule | None = None, turn_gaps=None) -> list[tuple[int, int]]:
    """The walking bouts of ``steps`` (sorted by ``start_s``) under ``rule`` as ``(first, last + 1)`` row ranges,
    short ones included (:func:`detected_bouts` leaves those under ``min_strides`` out). Decision C180: under the
    ``rhythm`` gap an interval a walker's turn of ``turn_gaps`` (:class:`~pdrlearn.track.turn_gaps.TurnGaps`) fills
    ends no bout; the ``contact`` gap (mobgap's literal rule, L163) does not read it."""
    rule = rule or BoutRule()
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    if rule.gap == "contact":
        return _contact_bouts(st, rule.break_s)
    return bout_rows(st, min_s=rule.break_s, turn_gaps=turn_gaps)


def session_key(session) -> dict:
    """Decision L165: bouts.csv's key columns of a :class:`~pdrlearn.io.Session` - its name and meta.json's subject
    (:func:`pdrlearn.cohort.meta_user`, as track-all's ``subject``; None when meta.json names none) and, decision
    C100, meta.json's visit (:func:`pdrlearn.cohort.meta_visit`). ``session`` None (``run --protocol``: a live
    stream, no session folder): all None."""
    from pdrlearn.cohort import meta_user, meta_visit

    if session is None:
        return {"session": None, "subject": None, "visit": None}
    meta = session.meta or {}
    return {"session": session.name, "subject": meta_user(meta, getattr(session, "folder", None)),
            "visit": meta_visit(meta)}


def session_ids(session) -> dict:
    """Decision C100: summary.json's ``subject`` and ``visit`` - meta.json's, as bouts.csv's (:func:`session_key`);
    None when not named (or no session). ``track``, ``run`` and track-all's sessions write them."""
    key = session_key(session)
    return {"subject": key["subject"], "visit": key["visit"]}


def session_leg_m(session) -> float | None:
    """Decision L195: the walker's leg length (m) from the session's meta.json (:func:`pdrlearn.track.gait.leg_length`,
    L148), by which each bout's walking range is scaled; None without a body measure (or without a session)."""
    from pdrlearn.track.gait import leg_length

    return None if session is None else leg_length(session.meta).get("leg_length_m")


def track_bouts(result, session, rule: BoutRule | None = None) -> pd.DataFrame:
    """A written track's bouts.csv rows (track, run, the folder writer): :func:`detected_bouts` of ``result.steps``
    keyed by ``session`` (decision L165), each bout's walking range scaled to its leg (L195), the cadence withheld
    where W476 withholds the track's step count (W480), a gap the walker's turn fills no break under a rule that
    says so (C180 / C182: ``--corridor``)."""
    rule = rule or BoutRule()
    return detected_bouts(result.steps, rule, **session_key(session), leg_m=session_leg_m(session),
                          withhold_cadence=bool(result.info.get("step_count_unusable")),
                          turn_gaps=rule.turn_gaps(result.info))


def detected_bouts(steps: pd.DataFrame, rule: BoutRule | None = None, *, session: str | None = None,
                   subject: str | None = None, visit: str | None = None, leg_m: float | None = None,
                   withhold_cadence: bool = False, turn_gaps=None, edge_steps: str = "inner") -> pd.DataFrame:
    """One row per detected walking bout of a track's step table (:data:`BOUT_COLUMNS`, module docstring).

    ``session`` / ``subject`` / ``visit``: the session's name and meta.json's subject (decision L165) and visit
    (C100), repeated on every row (empty when not given); ``n_steps``: steps of both feet, as summary.json's
    ``n_steps_both_feet`` (decision L103:
    a foot track's 2 per stride of the tracked foot, an estimate; a lower-back track's detected steps);
    ``n_strides``: a foot track's strides (rows that are no foot-data gap, L67), a lower-back track's strides from
    contact k to k + 2 as mobgap forms them (its rows are its contacts, the last one a 0 m row: ``n_steps`` - 2);
    ``distance_m``: the rows' summed |length_m| (the track's ``distance_m`` sums the same); ``start_s`` / ``end_s``:
    the first row's start and the last row's end, ``duration_s`` their difference (the bout's first and last steps
    included: slower than its middle); ``speed_mps`` = distance / duration (``speed_m_s`` before E98);
    ``stride_length_m`` (decision L166): the mean stride length, a foot track's distance / strides, a lower-back
    track's 2 x the mean step length over its ``n_steps`` - 1 steps (the last row is the 0 m closing contact);
    ``contact_span_s``: from the bout's first initial contact (``event_s``) to its last; ``n_step_intervals``: the
    steps between them (contacts - 1; 2 per stride of a tracked foot, L66); ``cadence_spm``: :func:`cadence_spm` of
    those two (NaN with fewer than 2 contacts); ``longest_contact_gap_s`` (decision L163): the longest time between
    two consecutive contacts in the bout - under the ``rhythm`` rule it may exceed ``break_s`` (a turn or the rhythm
    took the rest), this column says so; ``data_gap_s`` (decision L269): the foot-data gaps (L67's gap rows) inside
    the bout, summed - a gap longer than ``break_s`` ends the bout under either rule, so this holds only shorter
    ones (0 without a gap; the bout's speed and cadence then include time whose steps are not known);
    ``n_turns``: the track's turns of at least ``turn_count_min_deg`` (L104) whose first turning interval ends in
    the bout (a turn after a pause counts in the bout it starts); decision L331: ``backward_fraction``, the
    bout's strides that travel backward (:func:`pdrlearn.track.evaluate.backward_travel`, L203) over ``n_strides``,
    and ``direction`` (:func:`bout_direction`: forward / backward / mixed; L581: side, with ``n_backward_strides`` /
    ``n_side_strides``), all None on a lower-back track;
    ``altitude_change_m``: the rows' summed ``dz_m`` (NaN without that column) and, decision W158, the ``pause_dz_m``
    of its rows after the first (the standstills inside the bout); ``altitude_change_before_m`` (W158): the first
    row's ``pause_dz_m``, the altitude change while the unit stood before the bout (a lift or escalator ride; 0
    without that column), which is no walking bout's; ``gait_out_of_range`` (decision L195): the bout's own
    cadence or speed is above L95's walking range for a leg of ``leg_m`` (m, L148; None = the adult range), judged
    on bouts of at least 5 strides (:func:`pdrlearn.track.gait.bout_range_flags`); decision L212: ``n_cv_strides``
    the bout's strides of the session's stride-time CV (L104 / L188's steady straight level forward strides of a
    foot track; 0 on the lower back, L104), and over them, with at least
    :data:`~pdrlearn.track.clinical.CV_BOUT_MIN_STRIDES` (L196's minimum), ``stride_time_cv_pct`` and
    ``stride_length_cv_pct`` (100 x SD / mean, SD with n - 1); NaN with fewer. Decision W480: ``withhold_cadence``
    (a lower-back track whose contacts W442 finds no step count, ``info["step_count_unusable"]``) leaves
    ``cadence_spm`` NaN, as summary.json's median cadence (W476), and the bouts' range is judged on the speed.
    Decision C180: ``turn_gaps`` (a lower-back track's :class:`~pdrlearn.track.turn_gaps.TurnGaps`,
    ``rule.turn_gaps(result.info)``): under the ``rhythm`` gap an interval a walker's turn fills ends no bout; the bout
    keeps its time (duration, speed, ``longest_contact_gap_s``) but ``contact_span_s`` / ``n_step_intervals`` and so
    ``cadence_spm`` leave it out (its turning steps were not detected, W331). Decision W602: ``edge_steps``
    ``"inner"`` (the default) takes a lower-back bout's ``contact_span_s`` / ``n_step_intervals`` (and so its cadence)
    from its second contact to its last-but-one (:func:`step_terms`; fewer than 4 contacts: 0 / 0, no cadence);
    ``"all"`` from its first to its last (L164 as before). A foot track's bouts take all."""
    from pdrlearn.track.evaluate import travel_masks
    from pdrlearn.track.gait import bout_range_flags

    rule = rule or BoutRule()
    if edge_steps not in EDGE_STEPS:
        raise ValueError(f"edge_steps={edge_steps!r}: give one of {', '.join(EDGE_STEPS)} (decision W602)")
    out = BoutsTable(columns=list(BOUT_COLUMNS))
    if not len(steps) or "start_s" not in steps:
        return out
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    foot = is_foot_table(st)
    if rule.trim_edges:  # decision W495: each bout's edge contacts left out
        return edge_trimmed(st, rule, session=session, subject=subject, visit=visit, leg_m=leg_m,
                            withhold_cadence=withhold_cadence, turn_gaps=turn_gaps)  # W602: edges already cut
    gap_len = data_gap_lengths(st)  # decision L269: a bout's own (shorter) data gaps, summed as data_gap_s
    gap = gap_len > 0
    length = st["length_m"].abs().to_numpy(float) if "length_m" in st else np.zeros(len(st))
    ic = st["event_s"].to_numpy(float) if "event_s" in st else st["start_s"].to_numpy(float)
    dz = st["dz_m"].to_numpy(float) if "dz_m" in st else np.full(len(st), np.nan)
    pause_dz = np.nan_to_num(st["pause_dz_m"].to_numpy(float)) if "pause_dz_m" in st else np.zeros(len(st))
    angles, first = turn_rows(st)
    turn_row = first[np.abs(angles) >= TURN_COUNT_MIN_DEG]
    _, steady = steady_rows(st)  # decision L212: the session CV's strides, each bout's own share of them
    stride_s = st["stride_time_s"].to_numpy(float) if "stride_time_s" in st else np.full(len(st), np.nan)
    stride_len = np.full(len(st), np.nan)
    stride_len[steady] = steady_stride_lengths(st, steady)
    masks = travel_masks(st)  # decisions L331 / L581: the strides' travelled direction (L203, L270); None: lower back
    # decision C180: the intervals a walker's turn fills (no break under the rhythm gap; out of the bout's cadence)
    filled = (turn_filled(st, min_s=rule.break_s, turn_gaps=turn_gaps) if rule.gap == "rhythm"
              else np.zeros(max(len(st) - 1, 0), dtype=bool))
    rows = []
    for a, b in bout_ranges(st, rule, turn_gaps):
        n_strides = int((~gap[a:b]).sum()) if foot else max(b - a - 2, 0)
        if n_strides < rule.min_strides:
            continue
        n_steps = 2 * n_strides if foot else b - a
        t0, t1 = float(st["start_s"].iloc[a]), float(st["end_s"].iloc[b - 1])
        dur = t1 - t0
        dist = float(length[a:b].sum())
        c = ic[a:b][np.isfinite(ic[a:b])]
        span = float(c[-1] - c[0]) if len(c) >= 2 else 0.0
        intervals = (2 if foot else 1) * max(len(c) - 1, 0)
        inner = edge_steps == "inner" and not foot  # decision W602: a lower-back bout's edge steps are out
        if inner or filled[a:b - 1].any():  # decision C180: the turn-filled intervals are out of the cadence's terms
            span, intervals = step_terms(ic[a:b], filled[a:b - 1], inner=inner)
            intervals *= 2 if foot else 1
        n_len = n_strides if foot else n_steps - 1  # L166: a foot row is a stride; a lower-back row a step
        rows.append({"session": session, "subject": subject, "visit": visit, "bout": len(rows) + 1, "start_s": t0,
                     "end_s": t1,
                     "duration_s": dur, "n_steps": n_steps, "n_strides": n_strides, "distance_m": dist,
                     "speed_mps": dist / dur if dur > 0 else np.nan,
                     "stride_length_m": (1 if foot else 2) * dist / n_len if n_len > 0 else np.nan,
                     "contact_span_s": span, "n_step_intervals": intervals,
                     "cadence_spm": cadence_spm(intervals, span),
                     "longest_contact_gap_s": float(np.diff(c).max()) if len(c) >= 2 else np.nan,
                     "data_gap_s": float(gap_len[a:b].sum()),
                     "n_turns": int(((turn_row >= a) & (turn_row < b)).sum()),
                     **bout_direction(None if masks is None else int(masks[0][a:b].sum()), n_strides,  # L331
                                      None if masks is None else int(masks[1][a:b].sum())),  # decision L581
                     "altitude_change_m": float(dz[a:b].sum() + pause_dz[a + 1:b].sum()),
                     "altitude_change_before_m": float(pause_dz[a]), **_bout_cvs(steady[a:b], stride_s[a:b],
                                                                                  stride_len[a:b])})
    if not rows:
        return out
    table = BoutsTable(rows, columns=list(BOUT_COLUMNS))
    if withhold_cadence:  # decision W480: W442's contacts are no step count (summary.json withholds it, W476)
        table["cadence_spm"] = np.nan
    table["gait_out_of_range"] = bout_range_flags(table, leg_m)  # decision L195
    return table


#: decision W495: the line that refuses ``trim_edges`` on a foot track (its rows are strides, not contacts)
FOOT_TRIM_LINE = ("--bout-rule mobgap-indip trims a lower-back bout's edge contacts (decision W495); a foot track's "
                  "rows are strides: use --bout-rule mobgap")


def check_bout_unit(rule: BoutRule | None, unit: str) -> None:
    """Decision W495 (amended, session 43): refuse ``rule``'s ``trim_edges`` (``--bout-rule mobgap-indip``) for a
    track of ``unit`` ``"foot"`` before any tracking, in :data:`FOOT_TRIM_LINE` (``track`` / ``track-all`` with
    ``--pipeline plasys`` once, a session ``--pipeline auto`` resolves to the foot before it is tracked, ``run`` with
    a foot bundle before its replay)."""
    if rule is not None and rule.trim_edges and unit == "foot":
        raise DataError(FOOT_TRIM_LINE)


def edge_trimmed(st: pd.DataFrame, rule: BoutRule, **keys) -> pd.DataFrame:
    """Decision W495 (``trim_edges``, ``--bout-rule mobgap-indip``): :func:`detected_bouts` of a lower-back step table
    ``st`` (sorted) with each bout the rule finds and keeps cut to its second contact .. its last-but-one: the rows
    between, the new last one made the bout's 0 m closing contact (``end_s`` = its contact, ``has_next`` false), so
    every measure (start, duration, steps, distance, speed, stride length, cadence) is the trimmed bout's by
    bouts.csv's own definitions. A bout of fewer than 2 contacts after the cut is left out. A foot track's rows are
    strides, not contacts: one error line."""
    from dataclasses import replace

    if is_foot_table(st):
        raise DataError(FOOT_TRIM_LINE)
    inner = replace(rule, min_strides=0, trim_edges=False)
    parts = []
    for a, b in bout_ranges(st, rule, keys.get("turn_gaps")):
        if max(b - a - 2, 0) < rule.min_strides:  # the rule keeps or drops the bout as found (its n_strides)
            continue
        sub = st.iloc[a + 1:b - 1].copy()
        if len(sub) < 2:
            continue
        last = sub.index[-1]
        sub.loc[last, "end_s"] = sub.loc[last, "start_s"]
        sub.loc[last, "length_m"] = 0.0
        if "has_next" in sub:
            sub.loc[last, "has_next"] = False
        parts.append(detected_bouts(sub, inner, **keys, edge_steps="all"))  # W602: its edges are already cut
    parts = [p for p in parts if len(p)]
    if not parts:
        return BoutsTable(columns=list(BOUT_COLUMNS))
    table = BoutsTable(pd.concat(parts, ignore_index=True), columns=list(BOUT_COLUMNS))
    table["bout"] = np.arange(1, len(table) + 1)
    return table


#: decision L331: bouts.csv's ``direction`` values; decision L581: ``side``
BOUT_DIRECTIONS = ("forward", "backward", "mixed", "side")


def bout_direction(n_backward: int | None, n_strides: int, n_side: int | None = 0) -> dict:
    """Decision L331: a bout's ``backward_fraction`` (``n_backward`` of its ``n_strides`` strides travel backward,
    L203) and ``direction``: ``forward`` at 0, ``backward`` at 1, ``mixed`` between; both None without a count (a
    lower-back track) or without a stride. Decision L581: ``n_backward_strides`` and ``n_side_strides`` (``n_side``:
    strides of side-stepping runs, L270's, which travel neither way); ``direction`` is ``forward`` only with neither,
    ``backward`` / ``side`` when every stride is one, else ``mixed``."""
    if n_backward is None or n_strides <= 0:
        return {"direction": None, "backward_fraction": None, "n_backward_strides": None, "n_side_strides": None}
    n_side = n_side or 0
    forward, backward, mixed, side = BOUT_DIRECTIONS
    kind = forward if n_backward == n_side == 0 else backward if n_backward == n_strides else \
        side if n_side == n_strides else mixed
    return {"direction": kind, "backward_fraction": n_backward / n_strides, "n_backward_strides": int(n_backward),
            "n_side_strides": int(n_side)}


def _bout_cvs(steady: np.ndarray, stride_s: np.ndarray, length_m: np.ndarray) -> dict:
    """Decision L212: a bout's ``n_cv_strides`` and, with at least CV_BOUT_MIN_STRIDES of them (L196), the
    stride-time and stride-length CVs of its steady strides (NaN otherwise)."""
    n = int(steady.sum())
    t, length = stride_s[steady], length_m[steady]
    length = length[np.isfinite(length)]
    return {"n_cv_strides": n, "stride_time_cv_pct": cv_pct(t) if n >= CV_BOUT_MIN_STRIDES else np.nan,
            "stride_length_cv_pct": cv_pct(length) if len(length) >= CV_BOUT_MIN_STRIDES else np.nan}


#: a track's walking-bout totals (cohort C25): sessions.csv's columns, summed per subject in subjects.csv
BOUT_TOTALS = ("bouts_distance_m", "bouts_time_s", "bouts_n_steps", "bouts_n_strides", "bouts_contact_span_s",
               "bouts_n_step_intervals")


def bout_totals(table: pd.DataFrame) -> dict:
    """The totals of :func:`detected_bouts`'s ``table`` (cohort C25): ``bouts_distance_m`` (summed ``distance_m``),
    ``bouts_time_s`` (summed ``duration_s``: the walking time in bouts), ``bouts_n_steps`` and ``bouts_n_strides``
    (summed counts), ``bouts_contact_span_s`` and ``bouts_n_step_intervals`` (summed: the pooled cadence's terms,
    decision L164); zeros for a track without bouts."""
    return {"bouts_distance_m": float(table["distance_m"].sum()), "bouts_time_s": float(table["duration_s"].sum()),
            "bouts_n_steps": int(table["n_steps"].sum()), "bouts_n_strides": int(table["n_strides"].sum()),
            "bouts_contact_span_s": float(table["contact_span_s"].sum()),
            "bouts_n_step_intervals": int(table["n_step_intervals"].sum())}


def bouts_summary(steps: pd.DataFrame, rule: BoutRule | None = None, table: pd.DataFrame | None = None, *,
                  leg_m: float | None = None, turn_gaps=None) -> dict:
    """summary.json's keys (decision L124): ``n_bouts`` (the rows :func:`detected_bouts` gives) and
    ``bout_definition``; decision L195: ``n_bouts_out_of_range`` and ``bouts_out_of_range`` (bout, start_s, end_s,
    cadence_spm, speed_mps of each bout whose ``gait_out_of_range`` is true). ``table``: :func:`detected_bouts`'s
    table of ``steps`` under ``rule`` when the caller has it already (``track`` and ``run`` write it as bouts.csv;
    decision E73: the bouts are detected once); ``leg_m`` scales the range and ``turn_gaps`` (C180) fills pauses
    when the table is detected here."""
    rule = rule or BoutRule()
    if table is None:
        table = detected_bouts(steps, rule, leg_m=leg_m, turn_gaps=turn_gaps)
    flagged = (table[table["gait_out_of_range"].eq(True)] if "gait_out_of_range" in table and len(table)
               else table.iloc[0:0])
    keys = ("bout", "start_s", "end_s", "cadence_spm", "speed_mps")
    return {"n_bouts": int(len(table)), "bout_definition": rule.record(), "n_bouts_out_of_range": int(len(flagged)),
            "bouts_out_of_range": [{k: (int(r[k]) if k == "bout" else float(r[k])) for k in keys}
                                   for _, r in flagged.iterrows()]}
