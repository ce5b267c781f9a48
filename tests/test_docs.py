"""The documentation: the reference generated from the JSON Schemas describes every key, the tutorials'
code runs as written, the README stays short and its links resolve, and the site builds with --strict."""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
SCHEMAS = ["case", "study", "config", "paper_values"]
BLOCK = re.compile(r"(?:<!-- illustrative: (?P<why>[^>]*?) -->\n)?```(?P<lang>\w+)\n(?P<body>.*?)```", re.S)


def _hooks():
    spec = importlib.util.spec_from_file_location("dccss_docs_hooks", DOCS / "hooks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("name", SCHEMAS)
def test_every_schema_key_has_a_description(name):
    keys = _hooks().schema_keys(name)
    assert len(keys) > 10
    assert [path for path, _, description in keys if not description.strip()] == []


@pytest.mark.parametrize("name", SCHEMAS)
def test_every_schema_key_appears_in_the_generated_reference(name):
    hooks = _hooks()
    page = hooks.SchemaPage(name).render()
    for path, _, description in hooks.schema_keys(name):
        key = path.rsplit(".", 1)[-1]
        assert f"`{key}`" in page, path
        assert hooks._cell(description)[:40] in page, path


def test_a_key_without_description_is_found(monkeypatch):
    """The check above can fail: a key added without a description is reported by its path."""
    from dccss import schema

    original = schema.schema("case")
    changed = {**original, "properties": {**original["properties"], "undocumented": {"type": "number"}}}
    monkeypatch.setattr(schema, "schema", lambda name: changed if name == "case" else original)
    keys = _hooks().schema_keys("case")
    assert [p for p, _, d in keys if not d] == ["undocumented"]


def test_cross_file_references_resolve_in_the_library():
    """The study file's and the configuration's devices are the case file's: the library resolves them."""
    from dccss.schema import errors

    device = {"R1": 1.0}
    found = errors("study", {"study": {"name": "x"}, "prototype": device, "excitation": {"kind": "sine"},
                             "models": ["compliant"], "sweep": {"h2": [0.1]}})
    assert [e.path for e in found] == [("prototype",)]


def _tutorial_blocks():
    for page in sorted((DOCS / "tutorials").glob("*.md")):
        for match in BLOCK.finditer(page.read_text(encoding="utf-8")):
            yield page, match


def _unrunnable(blocks) -> list:
    """The blocks that neither run (yaml with a '# file:' line or a snippet include, bash, python) nor say why not
    (an illustrative block's reason, of four words at least)."""
    out = []
    for page, m in blocks:
        lang, body, why = m["lang"], m["body"], m["why"]
        if why is not None:
            assert len(why.split()) >= 4, f"{page.name}: the reason for an illustrative block is too short"
        elif lang == "yaml" and not (body.startswith("# file: ") or body.startswith("--8<--")):
            out.append((page.name, body[:40]))
        elif lang not in ("yaml", "bash", "python"):
            out.append((page.name, lang))
    return out


def test_every_tutorial_block_runs_or_says_why_not():
    """Every code block of a tutorial is run by test_tutorial_runs (yaml with a '# file:' line is written,
    bash and python run), or is marked illustrative with the reason."""
    assert _unrunnable(_tutorial_blocks()) == []


@pytest.mark.parametrize("page", [pytest.param(p.name, marks=[pytest.mark.slow] if p.name == "one-case.md" else [])
                                  for p in sorted((DOCS / "tutorials").glob("*.md"))])  # one-case: 4 commands, 8 s
def test_tutorial_runs(page, tmp_path):
    """A tutorial's files are written and its commands and Python run, in order, in an empty folder."""
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
           "MPLBACKEND": "Agg"}
    ran = 0
    for _, m in _tutorial_blocks():
        if m.string != (DOCS / "tutorials" / page).read_text(encoding="utf-8") or m["why"] is not None:
            continue
        lang, body = m["lang"], m["body"]
        if lang == "yaml" and body.startswith("# file: "):
            name = body.splitlines()[0].removeprefix("# file: ").strip()
            (tmp_path / name).write_text(body, encoding="utf-8")
        elif lang == "bash":
            run = subprocess.run(["bash", "-euo", "pipefail", "-c", body], cwd=tmp_path, env=env,
                                 capture_output=True, text=True, timeout=600)
            assert run.returncode == 0, f"{page}:\n{body}\n{run.stderr[-2000:]}"
            ran += 1
        elif lang == "python":
            run = subprocess.run([sys.executable, "-c", body], cwd=tmp_path, env=env, capture_output=True, text=True,
                                 timeout=600)
            assert run.returncode == 0, f"{page}:\n{body}\n{run.stderr[-2000:]}"
            ran += 1
    if page == "one-case.md":
        assert ran >= 3 and (tmp_path / "theta2.png").stat().st_size > 10_000
        assert (tmp_path / "case.gif").exists() and (tmp_path / "case.png").exists()


def _how_to_blocks(page=None):
    for path in sorted((DOCS / "how-to").glob("*.md")) if page is None else [DOCS / "how-to" / page]:
        for match in BLOCK.finditer(path.read_text(encoding="utf-8")):
            yield path, match


def test_every_how_to_block_runs_or_says_why_not():
    """Every code block of a how-to guide is run by test_how_to_runs (yaml with a '# file:' line is written,
    bash and python run, a snippet include is the file it includes), or is marked illustrative with the reason."""
    assert _unrunnable(_how_to_blocks()) == []


#: how-to pages whose command is a shipped study's run, as written: their blocks run on that study's shared run
SHIPPED_RUN = {"intensity-and-fragility.md": "ida"}
HOW_TO_RUNS = sorted({p.name for p, m in _how_to_blocks() if m["why"] is None and m["lang"] in ("bash", "python")}
                     - set(SHIPPED_RUN))


@pytest.mark.slow
@pytest.mark.parametrize("page", HOW_TO_RUNS)
def test_how_to_runs(page, tmp_path):
    """A how-to guide's files are written and its commands and Python run, in order, in a copy of the project (its
    Snakefile, config, workflow and profiles): as a user runs them from the project's root."""
    import shutil

    for name in ("Snakefile", "config", "workflow", "profiles"):
        (shutil.copytree if (ROOT / name).is_dir() else shutil.copy)(ROOT / name, tmp_path / name)
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
           "MPLBACKEND": "Agg"}
    ran = 0
    for _, m in _how_to_blocks(page):
        lang, body = m["lang"], m["body"]
        if m["why"] is not None:
            continue
        if lang == "yaml" and body.startswith("# file: "):
            path = tmp_path / body.splitlines()[0].removeprefix("# file: ").strip()
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(body, encoding="utf-8")
        elif lang == "yaml":  # a snippet include: the file is the project's own
            assert (tmp_path / body.split('"')[1]).is_file(), body
        else:
            command = ["bash", "-euo", "pipefail", "-c", body] if lang == "bash" else [sys.executable, "-c", body]
            run = subprocess.run(command, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
            assert run.returncode == 0, f"{page}:\n{body}\n{run.stdout[-1000:]}{run.stderr[-2000:]}"
            ran += 1
    assert ran >= 1


def test_the_intensity_how_to_runs_on_the_shipped_study(shipped_study):
    """The intensity how-to's command is the shipped study's run (tests/test_workflow.py compares its figures with
    the committed ones): its blocks run on that run, the command as written."""
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
           "MPLBACKEND": "Agg"}
    work = shipped_study("ida")
    commands = [m for _, m in _how_to_blocks("intensity-and-fragility.md") if m["why"] is None]
    assert [m["lang"] for m in commands] == ["yaml", "bash", "python"]
    assert commands[0]["body"].strip() == '--8<-- "config/studies/ida.yaml"'
    assert commands[1]["body"].strip() == "snakemake --profile profiles/default --configfile config/studies/ida.yaml"
    run = subprocess.run([sys.executable, "-c", commands[2]["body"]], cwd=work, env=env, capture_output=True,
                         text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-2000:]
    assert float(run.stdout) > 0.0


def test_how_to_case_files_are_valid(tmp_path, capsys):
    """The how-to guides' complete case and study files ('# file:', relative to the project's root, beside its
    shipped records) pass `dccss check`."""
    import shutil

    from dccss.cli import main

    shutil.copytree(ROOT / "config" / "studies" / "records", tmp_path / "config" / "studies" / "records")
    checked = 0
    for page in sorted((DOCS / "how-to").glob("*.md")):
        for m in BLOCK.finditer(page.read_text(encoding="utf-8")):
            if m["lang"] == "yaml" and m["body"].startswith("# file: "):
                path = tmp_path / m["body"].splitlines()[0].removeprefix("# file: ").strip()
                path.write_text(m["body"], encoding="utf-8")
                code = main(["check", str(path)])
                assert code == 0, f"{page.name}: {capsys.readouterr()}"
                checked += 1
    assert checked >= 3


def test_readme_is_short_and_its_links_resolve():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 150
    links = re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", text)
    local = [link for link in links if not re.match(r"https?://", link)]
    assert len(local) >= 10
    assert [link for link in local if not (ROOT / link).exists()] == []


def test_readme_reaches_the_asked_pages():
    """From the README, one link reaches each of: how to run a record suite, what `capacity: stop` does,
    why the paper's Eq. 30 is +0.248 m (two clicks at most: the README, then the page), and every how-to guide
    and explanation of the site (the intensity how-to, the friction and performance explanations were missing)."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    pages = {(ROOT / link).resolve() for link in re.findall(r"\]\((docs/[^)#\s]+)", text)}
    wanted = {"record suite": ("## Record suites", DOCS / "how-to/records.md"),
              "capacity: stop": ("| `stop` |", DOCS / "reference/failures.md"),
              "Eq. 30": ("+0.248", DOCS / "explanation/errata.md")}
    # every how-to and explanation page the site's navigation lists
    nav = re.findall(r":\s*((?:how-to|explanation)/[\w-]+\.md)", (ROOT / "mkdocs.yml").read_text(encoding="utf-8"))
    wanted.update({name: ("# ", DOCS / name) for name in nav})
    for what, (needle, page) in wanted.items():
        assert page.resolve() in pages, what
        assert needle in page.read_text(encoding="utf-8"), what


@pytest.mark.slow
def test_the_site_builds_strict(tmp_path):
    """`mkdocs build --strict`: a broken link, a missing page or a docstring mkdocstrings cannot read fails."""
    run = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-d", str(tmp_path / "site")],
                         cwd=ROOT, capture_output=True, text=True, env={**os.environ, "NO_MKDOCS_2_WARNING": "1"},
                         timeout=900)
    assert run.returncode == 0, run.stderr[-3000:]
    site = tmp_path / "site"
    case = (site / "reference/case-file/index.html").read_text(encoding="utf-8")
    assert "on_failure" in case and "spectral_scale" in case
    assert "dccss run" in (site / "reference/cli/index.html").read_text(encoding="utf-8")
    assert (site / "figures/fig07.png").exists() and (site / "figures/validation/index.html").exists()
    assert "theta2_stick" in (site / "reference/datasets/index.html").read_text(encoding="utf-8")


@pytest.mark.slow
def test_the_workflow_meets_the_catalogs_standardized_usage():
    """The Snakemake workflow catalog's rules: the workflow in workflow/Snakefile, config/README.md, a
    .snakemake-workflow-catalog.yml, and its linter content with the shipped default config."""
    import yaml

    assert (ROOT / "workflow" / "Snakefile").is_file() and (ROOT / "config" / "README.md").is_file()
    usage = yaml.safe_load((ROOT / ".snakemake-workflow-catalog.yml").read_text(encoding="utf-8"))["usage"]
    assert usage["software-stack-deployment"] and "--profile profiles/default" in usage["mandatory-flags"]["flags"]
    for args in ([], ["--configfile", "config/studies/pad_shape.yaml"]):
        run = subprocess.run([sys.executable, "-m", "snakemake", "--lint", *args], cwd=ROOT, capture_output=True,
                             text=True, timeout=300)
        assert run.returncode == 0 and "Congratulations" in run.stdout + run.stderr, run.stdout + run.stderr


def test_the_api_pages_names_are_importable_from_dccss():
    """The API page says its names import from ``dccss``: Structure and load_case did not."""
    import dccss

    page = (DOCS / "reference/api.md").read_text().split("## Adding a model")[0]
    names = [path.rsplit(".", 1)[-1] for path in re.findall(r"^::: (dccss\.[\w.]+)", page, re.MULTILINE)]
    assert len(names) > 10
    for name in names:
        assert getattr(dccss, name, None) is not None or importlib.util.find_spec(f"dccss.{name}"), name
        exec(f"from dccss import {name}", {})
