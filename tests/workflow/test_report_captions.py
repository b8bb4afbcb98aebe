"""Every figure of `snakemake --report` has a caption that names the report's
figure it corresponds to and says what to look at (issue #6).

The figures are found by reading workflow/rules/*.smk as text (every
`report(<path>, ..., caption=...)`), so the fast tests need no Snakemake run.
A caption is a Jinja template (Snakemake renders it with `snakemake.wildcards`
and `snakemake.config`, whose `scene_definitions` hold the scene files); it is
rendered here the same way for every scene of config/scenes/ (and one
`<scene>@<preset>` run) and must then
- cite a figure of the report ("Fig. 7.1", "Figs. 7.2 and 7.3") or say
  explicitly that it is "no figure of the report";
- cite only figures that exist: the report's list of figures has, per chapter
  2 ... 10, the counts in REPORT_FIGURES;
- contain a "Look at ..." sentence;
- be valid reStructuredText (docutils, as Snakemake converts it, no warning).
The slow test builds the HTML report of a small finished run and finds each
shown figure's references in it.
"""

from __future__ import annotations

import re
from pathlib import Path
from types import SimpleNamespace

import jinja2
import pytest
import yaml

from .conftest import REPO, copy_workflow, snakemake

RULES = REPO / "workflow" / "rules"
CAPTIONS = REPO / "workflow" / "report"
#: the workflow's description page (the Snakefile's `report:`), no caption
DESCRIPTION = CAPTIONS / "workflow.rst"
#: figures per chapter in the report's list of figures (Figure 2.1 ... 2.13, 3.1 ... 3.9, ...)
REPORT_FIGURES = {2: 13, 3: 9, 4: 3, 5: 4, 6: 23, 7: 14, 8: 28, 9: 5, 10: 2}
NUMBER = r"\d+\.\d+"
#: "Fig. 7.1", "Figs. 2.11 and 2.12", "Figs. 7.7 to 7.9", "Figs. 7.11-7.14", "Figs. 7.10, 7.14, 8.24"
FIGURE_REFERENCE = re.compile(
    rf"Figs?\.\s*{NUMBER}(?:(?:\s*,\s*|\s+and\s+|\s+to\s+|\s*-\s*){NUMBER})*")
NO_FIGURE = re.compile(r"no figure of the report", re.I)
LOOK_AT = re.compile(r"\bLook\s+at\b")


def _closing_paren(text: str, start: int) -> int:
    """Index of the parenthesis closing the one at text[start], skipping string literals."""
    depth, i, quote = 0, start, None
    while i < len(text):
        c = text[i]
        if quote:
            if c == "\\":
                i += 1
            elif c == quote:
                quote = None
        elif c in "\"'":
            quote = c
        elif c == "(":
            depth += 1
        elif c == ")":
            depth -= 1
            if depth == 0:
                return i
        i += 1
    raise ValueError(f"unbalanced parenthesis from offset {start}")


def report_calls() -> list[dict]:
    """Every `report(...)` of workflow/rules/*.smk: rule file, figure path, caption file."""
    calls = []
    for smk in sorted(RULES.glob("*.smk")):
        text = smk.read_text()
        for m in re.finditer(r"(?<![\w.])report\(", text):
            body = text[m.end():_closing_paren(text, m.end() - 1)]
            path = re.match(r"\s*f?[\"']([^\"']+)[\"']", body)
            caption = re.search(r"caption\s*=\s*[\"']([^\"']+)[\"']", body)
            labels = re.search(r"labels\s*=\s*(\{.*\})", body, flags=re.S)
            calls.append({
                "where": f"{smk.name}:{text.count(chr(10), 0, m.start()) + 1}",
                "figure": path.group(1) if path else None,
                "caption": (smk.parent / caption.group(1)).resolve() if caption else None,
                "labels": labels.group(1) if labels else None,
            })
    return calls


def scene_definitions() -> dict:
    return {p.stem: yaml.safe_load(p.read_text()) or {}
            for p in sorted((REPO / "config" / "scenes").glob("*.yaml"))}


def render(caption: Path, scene: str | None, scenes: dict) -> str:
    """The caption as Snakemake renders it (same Jinja options) for one scene."""
    env = jinja2.Environment(trim_blocks=True, lstrip_blocks=True)
    wildcards = SimpleNamespace(scene=scene) if scene else SimpleNamespace()
    stub = SimpleNamespace(wildcards=wildcards, config={"scene_definitions": scenes})
    return env.from_string(caption.read_text()).render(snakemake=stub)


def figure_references(text: str) -> list[str]:
    return [" ".join(m.group(0).split()) for m in FIGURE_REFERENCE.finditer(text)]


def per_scene(call: dict) -> bool:
    return "{scene}" in (call["figure"] or "")


CALLS = report_calls()


def test_report_usages_found():
    """The parser sees the report figures of the rules (11 at the time of writing)."""
    assert len(CALLS) >= 10, CALLS
    assert all(c["figure"] and c["figure"].endswith(".png") for c in CALLS), CALLS


def test_every_report_figure_has_a_caption_file_and_every_caption_a_figure():
    for call in CALLS:
        assert call["caption"] is not None, f"{call['where']}: report() without caption="
        assert call["caption"].parent == CAPTIONS, f"{call['where']}: caption outside {CAPTIONS}"
        assert call["caption"].exists(), f"{call['where']}: no caption file {call['caption']}"
    unused = ({p.name for p in CAPTIONS.glob("*.rst")} - {c["caption"].name for c in CALLS}
              - {DESCRIPTION.name})
    assert not unused, f"caption files no rule uses: {sorted(unused)}"


@pytest.mark.parametrize("call", CALLS, ids=[c["where"] for c in CALLS])
def test_caption_names_a_report_figure_and_what_to_look_at(call):
    from docutils.core import publish_parts

    scenes = scene_definitions()
    # every scene, and one `<scene>@<preset>` run (a scene at another preset)
    for scene in ([*sorted(scenes), f"{min(scenes)}@draft"] if per_scene(call) else [None]):
        text = render(call["caption"], scene, scenes)
        where = f"{call['caption'].name} rendered for scene {scene}"
        refs = figure_references(text)
        assert refs or NO_FIGURE.search(text), (
            f"{where}: names no figure of the report ('Fig. N.M') and does not say "
            f"'no figure of the report':\n{text}")
        for ref in refs:
            for number in re.findall(NUMBER, ref):
                chapter, figure = (int(x) for x in number.split("."))
                assert 1 <= figure <= REPORT_FIGURES.get(chapter, 0), (
                    f"{where}: {ref!r} cites Figure {number}, which the report does not have")
        assert LOOK_AT.search(text), f"{where}: no 'Look at ...' sentence:\n{text}"
        publish_parts(text, writer="html",  # raises on a warning
                      settings_overrides={"halt_level": 2, "report_level": 5})


# --- the HTML report of a small finished run ------------------------------------------------

REPORT_RUN = ("--config", "scenes=[profile_cosine,expectation_unit,greenwood_williamson]",
              "accuracy=draft", "studies=False")


@pytest.mark.slow
@pytest.mark.workflow
def test_html_report_contains_every_caption_figure_reference(tmp_path):
    """Three analytic scenes at draft (surface, expectation, interface and
    asperities figures, 4 of the caption files), then `snakemake --report`:
    the file exists, it opens with the workflow's description
    (workflow/report/workflow.rst), every figure's labels are in it, and for every
    figure of the run the report holds each figure reference and the 'Look at'
    sentence of its rendered caption."""
    workdir = copy_workflow(tmp_path)
    snakemake(workdir, *REPORT_RUN)
    snakemake(workdir, "--report", "report.html", *REPORT_RUN)
    html = workdir / "report.html"
    assert html.exists() and html.stat().st_size > 0
    # captions sit in the page as HTML inside a JavaScript string: newlines escaped
    page = " ".join(html.read_text().replace("\\n", " ").split())
    by_name = {Path(c["figure"]).name: c for c in CALLS if per_scene(c)}
    scenes = scene_definitions()
    shown = sorted((workdir / "results").glob("*/figures/*.png"))
    assert {p.name for p in shown} >= {"surface.png", "expectation.png", "interface.png",
                                       "asperities.png"}, shown
    description = " ".join(DESCRIPTION.read_text().split())
    assert description[:60] in page, "the workflow description is not in report.html"
    labels = {c["figure"].rsplit("/", 1)[-1]: re.search(r'"figure": "([^"]+)"', c["labels"]).group(1)
              for c in CALLS if per_scene(c)}
    for png in shown:
        assert f'"{labels[png.name]}"' in page or labels[png.name] in page, png.name
    for png in shown:
        scene = png.parent.parent.name
        text = render(by_name[png.name]["caption"], scene, scenes)
        refs = figure_references(text) or [NO_FIGURE.search(text).group(0)]
        for ref in refs:
            assert ref in page, f"{scene}/{png.name}: {ref!r} of its caption not in report.html"
        look = " ".join(text[LOOK_AT.search(text).start():].split())[:40]
        assert look in page, f"{scene}/{png.name}: {look!r} not in report.html"
