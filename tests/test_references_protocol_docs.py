"""Session 38, trial T4 findings 6 and 7: the thesis' full citation (README, docs/references.md, CITATION.cff) and
the user docs' "Differences from the thesis protocol" section, checked against what the simulator does."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parents[1]
THESIS = "All Over the Place Localization System"


def test_citation_cff_readme_and_references_cite_the_thesis_in_full():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software" and cff["authors"] and cff["title"]
    thesis = cff["references"][0]
    assert (thesis["type"], thesis["title"], thesis["year"]) == ("thesis", THESIS, 2015)
    assert thesis["authors"][0] == {"family-names": "Anacleto", "given-names": "Ricardo Manuel Soares"}
    assert "Universidade do Minho" in thesis["institution"]["name"]
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    refs = readme[readme.index("\n## References\n"):]
    assert "Ricardo Manuel Soares Anacleto" in refs and THESIS in refs and "Universidade do Minho, June 2015" in refs
    doc = (ROOT / "docs/references.md").read_text(encoding="utf-8")
    assert "@phdthesis{" in doc and THESIS in doc
    dois = [r["doi"] for r in cff["references"] if "doi" in r]
    assert len(dois) == 3 and all(d in doc for d in dois)
    for who in ("Basso et al. 2017", "Basso et al. 2021", "Alvarez et al. 2012", "Colombo et al. 2014"):
        assert who in doc


def test_protocol_differences_section_says_what_the_simulator_does():
    from pdrlearn.sim import simulate

    doc = (ROOT / "docs/characterization.md").read_text(encoding="utf-8")
    sec = doc[doc.index("### Differences from the thesis protocol"):]
    sec = sec[:sec.index("\n### ", 5)]
    for what in ("C69", "C70", "strides of one foot", "only climbs", "thresholds=\"thesis\""):
        assert what in sec, what
    d = simulate("D", user_seed=9664)
    terrain = set(d.steps["terrain"])
    assert "up" in terrain and "down" not in terrain  # the doc's "scenario `D` ... only climbs"
    dur = (d.steps["end_s"] - d.steps["start_s"]).to_numpy()
    assert np.median(dur) > 0.8  # a labelled row is a stride of one foot (~1 s at normal speed), not a step
    assert np.allclose(d.steps["start_s"].to_numpy()[1:6], d.steps["end_s"].to_numpy()[:5])
    assert not re.search(r"scenario `?D`? \(stairs up, down", doc)
