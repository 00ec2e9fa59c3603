"""Decision B184: ``pdrlearn run`` prints the replayed tracker's first few gap lines (decision E30: one per gap,
as a live tracker must) and then one line counting the rest: a BLE session with 5 % of its samples lost in bursts
printed 254 lines."""

from __future__ import annotations

import logging
import re

#: the runtime tracker's gap line (decision E30): "<streams>: no samples for 0.27 s (...) ... (decision E30)"
_GAP = re.compile(r"no samples for ([0-9.]+) s .*\(decision E30\)$")


class GapLines(logging.Filter):
    """While entered, the ``pdrlearn.runtime.tracker`` logger passes its first :attr:`keep` gap lines and counts
    the others (their number and seconds without samples); on exit one warning names ``where`` and the rest."""

    keep = 3

    def __init__(self, where: str) -> None:
        super().__init__()
        self.where, self.n, self.hidden, self.hidden_s = where, 0, 0, 0.0
        self._log = logging.getLogger("pdrlearn.runtime.tracker")

    def filter(self, record: logging.LogRecord) -> bool:
        m = _GAP.search(record.getMessage())
        if m is None:
            return True
        self.n += 1
        if self.n <= self.keep:
            return True
        self.hidden += 1
        self.hidden_s += float(m.group(1))
        return False

    def __enter__(self) -> GapLines:
        self._log.addFilter(self)
        return self

    def __exit__(self, *exc) -> None:
        self._log.removeFilter(self)
        if self.hidden:
            logging.getLogger("pdrlearn.cli").warning(
                "%s: %d gaps in all (%d more not printed, %.2f s without samples; decisions E30, B184): if they are "
                "many, check the Bluetooth link or the recorder", self.where, self.n, self.hidden, self.hidden_s)
