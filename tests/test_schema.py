"""Input files against their JSON Schemas (dccss.schema, dccss/schemas): valid schemas, the committed
files valid, the project's wording of every kind of error, and one source for the vocabularies."""

from pathlib import Path

import pytest
import yaml
from jsonschema import Draft202012Validator

from dccss import schema
from dccss.paper import validation as V

ROOT = Path(__file__).resolve().parents[1]
SCHEMAS = sorted(p.name.removesuffix(".schema.yaml") for p in (ROOT / "dccss/schemas").glob("*.schema.yaml"))
VALUES = yaml.safe_load((ROOT / "config/paper_values.yaml").read_text())
ENTRY = VALUES["values"][0]


@pytest.mark.parametrize("name", SCHEMAS)
def test_each_schema_is_a_valid_draft_2020_12_schema(name):
    Draft202012Validator.check_schema(schema.schema(name))


def test_the_committed_paper_values_follow_their_schema():
    assert schema.errors("paper_values", VALUES) == []


def test_the_vocabularies_come_from_the_schema():
    spec = schema.schema("paper_values")["$defs"]
    assert list(V.UNITS) == spec["unit"]["enum"]  # the factors are Python's, the names the schema's
    assert V.RELATIONS == ("within", "greater", "less") and V.LAWS == ("value", "ratio", "per_cubed_step")


@pytest.mark.parametrize("document, owner, message", [
    ({"values": [{**ENTRY, "relation": "about"}]}, ("values", 0),
     "relation 'about' is not one of ['within', 'greater', 'less']"),
    ({"values": [{k: v for k, v in ENTRY.items() if k not in ("source", "unit")}]}, ("values", 0),
     "missing key(s) ['source', 'unit']"),
    ({"values": [{**ENTRY, "reasn": "x", "nte": "y"}]}, ("values", 0),
     "unknown key(s) ['nte', 'reasn']; known: ['description', 'expect', 'id', 'note', 'quantity', 'reading', "
     "'reason', 'relation', 'source', 'tolerance', 'unit', 'value']"),
    ({"values": [{**ENTRY, "tolerance": -0.5}]}, ("values", 0), "tolerance -0.5 is negative"),
    ({"values": [{**ENTRY, "value": "8.5"}]}, ("values", 0), "value '8.5' is not a number"),
    ({"values": [{**ENTRY, "value": True}]}, ("values", 0), "value True is not a number"),
    ({"values": [{**ENTRY, "expect": "as_printed"}]}, ("values", 0), "expect 'as_printed' is not a list of variants"),
    ({"values": [{**ENTRY, "reading": {"label": "l"}}]}, ("values", 0),
     "reading: missing key(s) ['quantity', 'expect']"),
    ({"values": [{**ENTRY, "reading": {"label": "l", "quantity": {"kind": "k"}, "expect": 3}}]}, ("values", 0),
     "reading.expect 3 is not a list of variants"),
    ({"values": 3}, (), "values 3 is not a list"),
    ({"values": [], "extra": 1}, (), "unknown key(s) ['extra']; known: ['readings', 'values']"),
    ([1], (), "[1] is not a mapping"),
])
def test_errors_name_the_key_the_value_and_what_is_allowed(document, owner, message):
    found = schema.errors("paper_values", document)
    assert [(e.owner, e.message) for e in found] == [(owner, message)]


def test_errors_come_in_the_order_of_the_file(tmp_path):
    bad = [{**ENTRY, "id": "a", "unit": "degrees"}, {**ENTRY, "id": "b"}, {**ENTRY, "id": "c", "relation": "x"}]
    path = tmp_path / "values.yaml"
    path.write_text(yaml.safe_dump({"values": bad}))
    with pytest.raises(ValueError) as err:
        V.load_values(path, V.catalogue_from_config(yaml.safe_load((ROOT / "config/config.yaml").read_text())))
    lines = str(err.value).splitlines()
    assert lines[0].startswith("paper value 'a': unit 'degrees' is not one of ['m', 'cm'")
    assert lines[-1].startswith("paper value 'c': relation 'x' is not one of")
    assert not any(line.startswith("paper value 'b'") for line in lines)


# --- the study file --------------------------------------------------------------------------------
def study(**changes):
    config = yaml.safe_load((ROOT / "config/studies/pad_shape.yaml").read_text())
    return {**config, **changes}


@pytest.mark.parametrize("name", ["pad_shape", "ground_motion", "dt_convergence", "bidirectional"])
def test_the_shipped_studies_follow_the_schema(name):
    assert schema.errors("study", yaml.safe_load((ROOT / f"config/studies/{name}.yaml").read_text())) == []


@pytest.mark.parametrize("changes, message", [
    (dict(study={"name": "x", "description": 3}), "study.description 3 is not a string"),
    (dict(models=["compliant", "compliant"]), "models ['compliant', 'compliant'] has non-unique elements"),
])
def test_a_study_the_python_checks_pass_is_still_held_to_its_schema(changes, message):
    from dccss.studies import Study, StudyError

    with pytest.raises(StudyError) as err:
        Study.from_config(study(**changes), ROOT / "config/studies")
    assert str(err.value) == message


def test_the_study_schema_and_the_library_agree_on_the_vocabularies():
    from dccss.mechanics.capacity import CAPACITY_POLICIES
    from dccss.mechanics.kinematics import NORMALS
    from dccss.mechanics.newton import FAILURE_POLICIES
    from dccss.studies import spec

    props = schema.schema("study")["properties"]
    assert tuple(props["normals"]["enum"]) == NORMALS
    assert tuple(props["capacity"]["enum"]) == CAPACITY_POLICIES
    assert set(props["on_failure"]["enum"]) == set(FAILURE_POLICIES)
    assert spec.KEYS == set(props) and spec.REQUIRED == tuple(schema.schema("study")["required"])


# --- the case file ----------------------------------------------------------------------------------
CASE = {"prototype": "DFP1", "excitation": {"kind": "sine", "amplitude": 0.19, "omega": 30.0, "duration": 0.2},
        "dt": 0.01, "model": "stick_slip"}


def test_the_case_keys_and_defaults_come_from_the_schema():
    from dccss import case

    assert case.REQUIRED == ("prototype", "excitation", "dt", "model")
    assert case.OPTIONAL == {"theta2_0": 0.0, "normals": "signed", "newton": None, "id": None,
                             "capacity": "continue", "on_failure": "error", "structure": None, "slider": "rigid",
                             "friction": None}
    assert case.EXCITATION_KEYS["record"] == ("file",)
    assert case.EXCITATION_OPTIONAL["record"] == ("scale", "window", "baseline", "units", "azimuth", "rotation",
                                                  "component", "vertical", "pair_span")
    assert schema.errors("case", CASE) == []


@pytest.mark.parametrize("changes", [
    {"model": None}, {"colour": "red"}, {"dt": [0.01]}, {"dt": "1e-3"}, {"dt": 0.0}, {"capacity": "halt"},
    {"on_failure": "stop"}, {"newton": {"tol": 1e-12, "iterations": 3}}, {"excitation": {"kind": "sine", "omega": 1.0}},
    {"excitation": {"kind": "record", "file": "a.AT2", "baseline": "cubic"}},
    {"excitation": {"kind": "table", "file": "a.csv", "window": [0, 1]}},
])
def test_the_schema_refuses_what_the_case_checks_refuse(changes):
    """Both statements of the structure agree: a structural mistake the Python checks name is one the
    schema finds too (the Python checks answer first, with the better words)."""
    from dccss.case import CaseError, case_from

    bad = {k: v for k, v in {**CASE, **changes}.items() if v is not None}
    assert schema.errors("case", bad)
    with pytest.raises(CaseError):
        case_from(bad)


def test_the_paper_config_follows_its_schema_and_the_library_agrees():
    from dccss.mechanics.kinematics import NORMALS

    config = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    assert schema.errors("config", config) == []
    assert tuple(schema.schema("config")["$defs"]["normals"]["enum"]) == NORMALS
