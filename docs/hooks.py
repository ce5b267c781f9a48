"""MkDocs hooks: the pages that are generated from the code, so that they cannot drift from it.

* ``<!-- dccss:schema NAME -->`` becomes the reference of ``dccss/schemas/NAME.schema.yaml``: one table
  per mapping (key, what is allowed, default, description);
* ``<!-- dccss:cli -->`` becomes the ``--help`` of ``dccss`` and of each of its commands;
* ``<!-- dccss:datasets -->`` becomes the variables and attributes of the datasets ``dccss`` writes,
  read off small runs of each kind;
* the committed figures, animations and ``figures/validation.md`` are served from ``figures/`` as they
  are (the validation report is a page of the site, not a copy).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MARKER = re.compile(r"<!-- dccss:(\w+)\s*(\S*)\s*-->")
PAGES = {"case": "case-file.md", "study": "study-file.md", "config": "config.md", "paper_values": "paper-values.md"}
TITLES = {"case-file.md": "case file", "study-file.md": "study file", "config.md": "configuration",
          "paper-values.md": "paper values"}
TYPE_NAMES = {"number": "a number", "integer": "an integer", "string": "a string", "array": "a list",
              "object": "a mapping", "boolean": "true or false", "null": "null"}


# ---------------------------------------------------------------------------------------------------
# JSON Schemas


def _cell(text) -> str:
    """A table cell: one line, pipes escaped, and a placeholder as <name> shown, not read as an HTML
    tag (outside code spans, where it is literal)."""
    parts = " ".join(str(text).split()).replace("|", "\\|").split("`")
    return "`".join(p if i % 2 else p.replace("<", "&lt;").replace(">", "&gt;") for i, p in enumerate(parts))


def _code(value) -> str:
    if value is None:
        return "`null`"
    if isinstance(value, bool):
        return f"`{str(value).lower()}`"
    return f"`{value}`"


class SchemaPage:
    """The reference of one schema: a table per mapping (the top level, each mapping nested in it, each
    mapping of ``$defs``), in the order met."""

    def __init__(self, name):
        from dccss.schema import schema

        self.name, self.root = name, schema(name)
        self.defs = self.root.get("$defs", {})
        self.sections: list[tuple[str, str, dict]] = []  # (title, anchor, object schema)

    def render(self) -> str:
        self._section("top level", "top-level", self.root)
        out, done = [_cell(self.root.get("description", "")), ""], 0
        while done < len(self.sections):  # a table may add the sections of the mappings nested in it
            title, anchor, obj = self.sections[done]
            done += 1
            out += [f"## `{title}` {{#{anchor}}}" if obj is not self.root else "## Top level {#top-level}", ""]
            if obj.get("description") and obj is not self.root:
                out += [_cell(obj["description"]), ""]
            out += self._table(obj, title, anchor)
            if done == len(self.sections):  # then the definitions the file refers to, in their order
                for key, sub in self.defs.items():
                    if self._is_mapping(sub):
                        self._section(key, f"def-{key}", sub)
        return "\n".join(out)

    @staticmethod
    def _is_mapping(sub) -> bool:
        return isinstance(sub, dict) and ("properties" in sub or "patternProperties" in sub)

    def _section(self, title, anchor, obj):
        if all(a != anchor for _, a, _ in self.sections):
            self.sections.append((title, anchor, obj))

    def _table(self, obj, title, anchor) -> list[str]:
        required = set(obj.get("required", []))
        rows = ["| key | allowed | default | description |", "|---|---|---|---|"]
        entries = list(obj.get("properties", {}).items())
        entries += [(f"<{pattern}>", sub) for pattern, sub in obj.get("patternProperties", {}).items()]
        extra = obj.get("additionalProperties")
        if isinstance(extra, dict):
            entries.append(("<name>", extra))
        for key, sub in entries:
            path = key if title == "top level" else f"{title}.{key}"
            allowed = self._allowed(sub, path, f"{anchor}-{re.sub(r'[^A-Za-z0-9_-]', '', key) or 'name'}")
            default = _code(sub["default"]) if "default" in sub else ""
            mark = " (required)" if key in required else ""
            rows.append(f"| `{key}`{mark} | {_cell(allowed)} | {default} | {_cell(self.description(sub))} |")
        rows.append("")
        cases = [(c["if"]["properties"]["kind"]["const"], c["then"]) for c in obj.get("allOf", []) if "if" in c]
        if cases:
            keyed = ", ".join(f"{_code(k)}: {self._allowed(then, title, anchor)}" for k, then in cases)
            rows += [f"Its other keys follow its `kind`: {keyed}.", ""]
        return rows

    def description(self, sub) -> str:
        """A key's description: its own, or that of the definition it refers to."""
        if not isinstance(sub, dict):
            return ""
        if sub.get("description"):
            return sub["description"]
        if "$ref" in sub:
            return self.description(self._target(sub["$ref"]))
        return ""

    def _target(self, ref) -> dict:
        from dccss.schema import schema

        where, _, pointer = ref.partition("#")
        defs = schema(where.removesuffix(".schema.yaml"))["$defs"] if where else self.defs
        return defs[pointer.rsplit("/", 1)[-1]]

    def _allowed(self, sub, path, anchor) -> str:
        if not isinstance(sub, dict):
            return ""
        if "$ref" in sub:
            where, name = sub["$ref"].partition("#")[0], sub["$ref"].rsplit("/", 1)[-1]
            target = self._target(sub["$ref"])
            if not self._is_mapping(target):
                return self._allowed(target, path, anchor)
            page = PAGES[where.removesuffix(".schema.yaml")] if where else ""
            return f"[`{name}`]({page}#def-{name})" + (f" (of the {TITLES[page]})" if page else "")
        if "const" in sub:
            return _code(sub["const"])
        if "enum" in sub:
            return "one of " + ", ".join(_code(v) for v in sub["enum"])
        for key in ("oneOf", "anyOf"):
            if key in sub:
                return " or ".join(self._allowed(s, path, anchor) for s in sub[key])
        if self._is_mapping(sub):
            self._section(path, anchor, sub)
            return f"a mapping: [`{path}`](#{anchor})"
        types = sub.get("type", [])
        types = types if isinstance(types, list) else [types]
        words = []
        for t in types:
            word = TYPE_NAMES.get(t, t)
            if t == "array" and isinstance(sub.get("items"), dict):
                word = f"a list of ({self._allowed(sub['items'], path + '[]', anchor + '-item')})"
            if t == "object" and isinstance(sub.get("additionalProperties"), dict):
                word = f"a mapping of names to ({self._allowed(sub['additionalProperties'], path + '.<name>', anchor)})"
            words.append(word)
        text = " or ".join(words) or "any value"
        bounds = [(k, s) for k, s in (("minimum", "≥"), ("exclusiveMinimum", ">"), ("maximum", "≤"),
                                      ("exclusiveMaximum", "<"), ("minItems", "at least"),
                                      ("minProperties", "at least")) if k in sub]
        if bounds:
            text += " " + ", ".join(f"{s} {sub[k]}" for k, s in bounds)
        if "pattern" in sub:
            text += f" matching `{sub['pattern']}`"
        if sub.get("uniqueItems"):
            text += ", no repeats"
        return text


def schema_keys(name) -> list[tuple[str, dict, str]]:
    """Every key of schema ``name`` (path, its schema, description), for the test that each is described."""
    page = SchemaPage(name)
    found: list[tuple[str, dict, str]] = []

    def walk(obj, path):
        if not isinstance(obj, dict):
            return
        if "$ref" in obj:
            return
        for key, sub in obj.get("properties", {}).items():
            found.append((f"{path}{key}", sub, page.description(sub)))
            walk(sub, f"{path}{key}.")
        for pattern, sub in obj.get("patternProperties", {}).items():
            found.append((f"{path}<{pattern}>", sub, page.description(sub)))
            walk(sub, f"{path}<{pattern}>.")
        for key in ("items", "additionalProperties"):
            walk(obj.get(key), path)
        for key in ("oneOf", "anyOf", "allOf"):
            for sub in obj.get(key, []):
                walk(sub, path)
                walk(sub.get("then") if isinstance(sub, dict) else None, path)

    walk(page.root, "")
    for key, sub in page.defs.items():
        walk(sub, f"$defs.{key}.")
    return found


# ---------------------------------------------------------------------------------------------------
# the command line


def _help(argv) -> str:
    from dccss import cli

    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.suppress(SystemExit):
        cli.main(argv)
    return out.getvalue()


def cli_page() -> str:
    os.environ["COLUMNS"] = "100"
    top = _help(["--help"])
    commands = re.search(r"\{([a-z,]+)\}", top).group(1).split(",")
    out = ["## `dccss`", "", "```text", top.rstrip(), "```", ""]
    for command in commands:
        out += [f"## `dccss {command}`", "", "```text", _help([command, "--help"]).rstrip(), "```", ""]
    return "\n".join(out)


# ---------------------------------------------------------------------------------------------------
# datasets


def _examples():
    from dccss import Oriented, Sine, simulate
    from dccss.excitation import Vertical, VerticalSine
    from dccss.mechanics.structure import Structure
    from dccss.paper.prototypes import DFP1

    sine = Sine(amplitude=0.05, omega=30.0, duration=0.03)
    return {
        ("A planar history", "What `dccss run` and `dccss.simulate` write for a one-component motion; stick-slip "
         "adds the end of each sticking phase (`_stick`)."):
            simulate(DFP1, sine, model="stick_slip", dt=0.01),
        ("A history in space", "Two components (a record pair, an x, y table, or a one-component input along an "
         "`azimuth`): the spatial models."):
            simulate(DFP1, Oriented(sine, 30.0), model="stick_slip", dt=0.01),
        ("What a structure adds", "With `structure:` (one component; a pair adds `_x` and `_y`)."):
            simulate(DFP1, sine, model="compliant", dt=0.01, structure=Structure(friction=0.05)),
        ("What a vertical component adds", "With `excitation.vertical` and a structure "
         "([the vertical component](../how-to/records.md#vertical)); an uplift adds `uplift_at_s`, "
         "`uplift_duration_s`, `uplift_count` and, under `capacity: stop`, `stopped_by`."):
            simulate(DFP1, Vertical(sine, VerticalSine(3.0, 40.0)), model="compliant", dt=0.01,
                     structure=Structure(friction=0.05)),
        ("An articulated slider {#articulated}", "With `slider: articulated` and no structure: the imposed "
         "displacement shared between the two surfaces, quasi-statically (one component, `friction: [mu1, mu3]`; "
         "[The articulated slider](../explanation/articulated-slider.md)). Its `model` attribute is `articulated` "
         "and it has none of the pad's variables (θ², the rise, the corners): each of its variables is listed. A "
         "half that reaches its ring adds `ring_<j>_reached_at_s` and `ring_<j>_exceeded_by_m` (j = 1, 3), and "
         "under `capacity: stop` or `error` `stopped_at_s` or `failure_time_s`."):
            simulate(DFP1, sine, model="compliant", dt=0.01, slider="articulated", friction=[0.03, 0.06]),
        ("An articulated slider under a structure", "With `slider: articulated` and a structure (`friction_on: "
         "surfaces`): the structure's variables, without the device's one friction state `z`, and each surface's "
         "friction state and coefficient; the ground displacement `Xg` beside the stroke. In two components every "
         "vector gains `_x` and `_y`, and `theta_1`, `theta_3` become `tilt_1`, `tilt_3` (each half's tilt from the "
         "vertical; `hinge_rotation` is then the angle between the halves, >= 0). A temperature law adds "
         "`surface_temperature_1` and `surface_temperature_3`, a vertical component its variables above."):
            simulate(DFP1, sine, model="compliant", dt=0.01,
                     structure=Structure([0.03, 0.06], 0.0, "surfaces", slider="articulated")),
    }


#: the examples whose variables are all listed (a dataset of its own kind), not only those not met before
COMPLETE = ("An articulated slider {#articulated}",)


def datasets_page() -> str:
    out, seen = [], set()
    for (title, what), ds in _examples().items():
        names = [n for n in [*ds.coords, *ds.data_vars] if n not in seen or title in COMPLETE]
        attrs = [a for a in ds.attrs if a not in seen]
        seen.update(names, attrs)
        out += [f"## {title}", "", what, "", "| variable | dimensions | units | long name |", "|---|---|---|---|"]
        for n in names:
            v = ds[n]
            out.append(f"| `{n}` | {', '.join(v.dims)} | {_cell(v.attrs.get('units', ''))} | "
                       f"{_cell(v.attrs.get('long_name', ''))} |")
        out += ["", "| attribute | example |", "|---|---|"]
        for a in attrs:
            value = str(ds.attrs[a])
            out.append(f"| `{a}` | {_cell(value if len(value) < 90 else value[:87] + '...')} |")
        out.append("")
    return "\n".join(out + _summaries())


def _summaries() -> list[str]:
    from dccss.mechanics import structure, summaries
    from dccss.studies.combine import STATISTICS

    out = ["## Study summaries {#study-summaries}", "",
           "A study's dataset (`results/studies/<name>/<name>.nc`) has a dimension `model` and one per sweep "
           "axis, and for each case:", "", "| variable | units | long name |", "|---|---|---|"]
    rows = {**summaries.specs(), **{f"{k} (bidirectional)": v for k, v in summaries.TILT_SUMMARIES.items()},
            **structure.SUMMARIES, **{f"{k} (with a vertical)": v for k, v in structure.VERTICAL_SUMMARIES.items()},
            **{f"{k} (comparing slider kinds)": v for k, v in structure.SURFACE_SUMMARIES.items()}}
    for name, (units, long_name) in rows.items():
        out.append(f"| `{name}` | {units} | {_cell(long_name)} |")
    out += ["", f"A `record` axis (a suite) adds, for every summary, `<name>_suite` with a `statistic` coordinate "
            f"({', '.join(f'`{s}`' for s in STATISTICS)}), and `record_pga`, `record_pgv`, `record_pgd`, "
            "`record_source`, `records_counted`, `records_failed`, `records_capacity_exceeded` (and, with a "
            "vertical, `records_uplift`) "
            "([A real record or a suite](../how-to/records.md#record-suites)).", "",
            "The summaries \"comparing slider kinds\" are there where a study has a `slider` axis or an articulated "
            "slider: an articulated slider's from each surface's own history, the rigid slider's from its stroke, "
            "its surfaces sliding in proportion (L_j / L of the stroke, no hinge rotation). The pad's summaries (θ², "
            "the rise, the corners) are the rigid pad's models' and NaN for an articulated slider's cases, whose "
            "`capacity_exceeded` and `capacity_time` say whether and when either half first reached its ring "
            "([The articulated slider](../how-to/articulated-slider.md#a-study-comparing-slider-kinds)).", ""]
    return out


# ---------------------------------------------------------------------------------------------------
# MkDocs events


def on_files(files, config):
    """Serve the committed figures, animations and validation report from ``figures/``."""
    from mkdocs.structure.files import File

    for path in sorted((ROOT / "figures").rglob("*")):
        if path.suffix in (".png", ".gif", ".md") and path.is_file():
            uri = path.relative_to(ROOT).as_posix()
            if files.get_file_from_path(uri) is None:
                files.append(File.generated(config, uri, abs_src_path=str(path)))
    return files


def on_page_markdown(markdown, page, config, files):
    def replace(match):
        kind, arg = match.group(1), match.group(2)
        if kind == "schema":
            return SchemaPage(arg).render()
        if kind == "cli":
            return cli_page()
        if kind == "datasets":
            return datasets_page()
        raise ValueError(f"{page.file.src_uri}: unknown marker dccss:{kind}")

    return MARKER.sub(replace, markdown)
