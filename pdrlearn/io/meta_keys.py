"""The top-level meta.json keys pdrlearn knows (decision B262): the ones it reads, and the ones its simulator,
importers (``pdrlearn import``, the external-data converters) and commands write. A key outside the set is named in
one line by ``pdrlearn info`` and ``pdrlearn track`` (it is not read: a typo, or a setting pdrlearn does not have).
"""

from __future__ import annotations

#: decision B262: keys pdrlearn reads (docs/bad-input.md "meta.json fields", docs/frames.md, docs/data.md ...)
READ = frozenset({
    "units", "frames", "frames_how", "force_frame", "placement", "instrumented_foot", "foot", "waist", "pelvis",
    "session", "subject", "visit", "labels", "reference", "imported", "resampled", "clocks", "clock_id",
    "clock_offset_s", "clock_drift_ppm", "recording_start", "utc_start_s", "start_datetime", "time_zone",
    "time_convention", "rate_hz", "height_m", "leg_length_m", "sensor_height_m", "foot_length_m", "foot_length_cm",
    "stride_length_m", "length_class_bounds_m", "distance_m", "dropped_samples", "n_ics", "n_strides", "n_steps",
    "n_turns", "terrain_counts", "caveats", "knobs", "source_project", "source_sdist", "same_sensor_data_as",
    "duplicate_of", "note", "protocol_stats",
    "belt_speed_mps",  # decision L321: a declared treadmill's belt speed
    "belt_incline_pct",  # decision L442: a declared treadmill's incline
    "walk_test_start_s",  # decision L642: a session's timed walk test's "go" (s)
    "full_scale",  # decision B456: the accelerometers' / gyroscopes' declared ranges
})
#: keys the simulator and the importers write as provenance (read by people, not by the pipelines)
WRITTEN = frozenset({
    # pdrlearn.sim.simulate
    "earth_field_enu_ut", "internal_rate_hz", "length_m_definition", "misalignment_deg", "scenario", "seed",
    "sensor_errors", "speed", "time_base", "user", "user_seed", "p0_hpa",
    # pdrlearn import, pdrlearn.io.external (gaitmap, mobgap, hapt) and the bundled datasets' converters
    "activity", "activity_seconds", "axes", "caveat", "cohort_meaning", "device_timestamp_step_ms", "duration_s",
    "files", "license", "magnetometer", "mag_norm_uT_mean", "n_samples", "rest_acc_first_0.5s_mps2",
    "rest_acc_lying_mps2", "rest_acc_mean_mps2", "rest_acc_norm_mps2", "rest_acc_standing_mps2", "sensor_hardware",
    "source_commit", "source_description", "source_files", "source_path_in_mat", "source_path_in_pickle",
    "source_repo", "source_sample_offset", "terrain_recording", "test", "trial", "part", "lines", "streams",
    "retimed", "stamp_rate_hz", "ambiguous_columns", "unused_columns",
    "split",  # pdrlearn split: the part's place in its session (decision B379)
    "source_local",  # pdrlearn fetch mobgap --from: the folder converted (decision C173)
})
KNOWN_META_KEYS = READ | WRITTEN


def unknown_meta_keys(meta: dict | None) -> list[str]:
    """Decision B262: the top-level keys of ``meta`` (meta.json) pdrlearn neither reads nor writes, in file order;
    keys starting with ``_`` or ``x_`` are the user's own (never named)."""
    return [k for k in (meta or {}) if isinstance(k, str) and k not in KNOWN_META_KEYS
            and not k.startswith(("_", "x_"))]


def unknown_keys_line(meta: dict | None, where: str) -> str | None:
    """Decision B262: one line naming meta.json's unknown top-level keys (None when there are none)."""
    keys = unknown_meta_keys(meta)
    if not keys:
        return None
    hint = (" (a treadmill: declare \"belt_speed_mps\", decision L321; docs/frames.md)"
            if any("treadmill" in k.lower() or "belt" in k.lower() for k in keys) else "")
    return (f"{where}/meta.json: key(s) {', '.join(repr(k) for k in keys)} not read by pdrlearn (a typo, or a "
            f"setting it does not have){hint}; prefix your own notes with x_ to keep this quiet (decision B262)")


def label_option(value, where: str, option: str, what: str, example: str, decision: str) -> str | None:
    """Decisions B345 (``import --subject``), B364 (``import --visit``, ``simulate --subject`` / ``--visit``): a
    subject id or visit name given on the command line, stripped, for meta.json (track-all pairs visits by them,
    cohort C22); None when not given; blank is one line naming the option (``where``: the command)."""
    if value is None:
        return None
    from pdrlearn.errors import DataError

    text = str(value).strip()
    if not text:
        raise DataError(f"{where}: {option} is empty; give the {what} (e.g. {option} {example}; decision {decision})")
    return text
