"""The record of a command's run, ``run.json``: :mod:`pdrlearn.provenance` (decision E169, session 35: a library
module, so that :func:`pdrlearn.write_track` records its run without importing the CLI), imported under the name the
commands use."""

from pdrlearn.provenance import (  # noqa: F401
    RECORDED_PACKAGES,
    given_options,
    input_hashes,
    invocation,
    model_record,
    redaction,
    run_record,
    set_command_line,
    software_record,
    write_run_json,
)
