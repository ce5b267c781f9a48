"""Input files against their JSON Schemas (``dccss/schemas/*.schema.yaml``, draft 2020-12).

A schema is the one statement of a file's structure: its keys, their types and allowed values.
The library checks a file against it here (``errors``) and the workflow reads the same file; the
modules that load a file check only what a schema cannot say (references to what a study runs,
units against dimensions, geometry). Errors are worded as the project words them: the key (a dotted
path from the object it belongs to), the value and what is allowed, e.g. ``relation 'about' is not
one of ['within', 'greater', 'less']`` or ``missing key(s) ['source']``. A schema may add to an
object or value ``x-expected`` (how a wrong type is described, e.g. "a list of variants").
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from importlib.resources import files

import yaml
from jsonschema import Draft202012Validator
from referencing import Registry, Resource
from referencing.jsonschema import DRAFT202012

TYPE_NAMES = {"number": "a number", "integer": "an integer", "string": "a string", "array": "a list",
              "object": "a mapping", "boolean": "true or false", "null": "empty"}


#: PyYAML's safe loader, its C implementation (libyaml, about 10 times faster) where installed: the same data
SAFE_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def load_yaml(stream):
    """``yaml.safe_load`` of a string or an open file, by ``SAFE_LOADER``."""
    return yaml.load(stream, Loader=SAFE_LOADER)  # noqa: S506 (a safe loader)


@cache
def schema(name) -> dict:
    """The schema ``dccss/schemas/<name>.schema.yaml``."""
    return load_yaml(files("dccss").joinpath("schemas", f"{name}.schema.yaml").read_text(encoding="utf-8"))


def _retrieve(uri):
    """Another schema of the package, for a reference such as ``case.schema.yaml#/$defs/device``."""
    return Resource.from_contents(schema(uri.removesuffix(".schema.yaml")), default_specification=DRAFT202012)


REGISTRY = Registry(retrieve=_retrieve)


@dataclass(frozen=True)
class SchemaError:
    """One error: where (``path``, keys and list indices from the file's top) and what (``message``,
    starting with the key relative to ``owner``, the path of the object the key belongs to)."""

    path: tuple
    owner: tuple
    message: str


def errors(name, instance) -> list[SchemaError]:
    """The errors of ``instance`` against schema ``name``, one per key (a mapping's missing keys, and
    its unknown keys, in one error each), in the order of the file."""
    found = sorted(Draft202012Validator(schema(name), registry=REGISTRY).iter_errors(instance),
                   key=lambda e: _order(e.absolute_path))
    out, seen = [], set()
    for err in found:
        path = tuple(err.absolute_path)
        if err.validator in ("required", "additionalProperties"):
            if (path, err.validator) in seen:
                continue
            seen.add((path, err.validator))
        out.append(_describe(err, path))
    return out


def _order(path):
    return [(0, p) if isinstance(p, int) else (1, str(p)) for p in path]


def _describe(err, path) -> SchemaError:
    kind, value, spec = err.validator, err.instance, err.schema
    owner, key = _owner(path)
    if kind in ("required", "additionalProperties"):
        where = f"{key}: " if key else ""
        if kind == "required":
            missing = [k for k in spec["required"] if k not in value]
            return SchemaError(path, owner, f"{where}missing key(s) {missing}")
        known = sorted(spec.get("properties", {}))
        unknown = sorted(str(k) for k in value if k not in spec.get("properties", {}))
        return SchemaError(path, owner, f"{where}unknown key(s) {unknown}; known: {known}")
    if kind == "enum":
        text = f"{value!r} is not one of {list(spec['enum'])}"
    elif kind == "type":
        types = spec["type"] if isinstance(spec["type"], list) else [spec["type"]]
        expected = spec.get("x-expected") or " or ".join(TYPE_NAMES.get(t, t) for t in types)
        text = f"{value!r} is not {expected}"
    elif kind == "minimum" and spec["minimum"] == 0:
        text = f"{value!r} is negative"
    else:
        text = err.message
    return SchemaError(path, owner, f"{key} {text}" if key else text)


def _owner(path):
    """The object a key at ``path`` belongs to: the nearest list item at or above it (or the top), and
    the dotted key from there ("" for the item itself)."""
    for cut in range(len(path), -1, -1):
        if cut == 0 or isinstance(path[cut - 1], int):
            return tuple(path[:cut]), ".".join(str(p) for p in path[cut:])
    return (), ""
