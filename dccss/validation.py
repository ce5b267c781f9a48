"""Check the numbers the paper states against the computed datasets.

``config/paper_values.yaml`` lists each number: value, unit, tolerance, source, the quantity to
compute (a ``kind`` below with its parameters) and the variants expected to reproduce it. A
variant is a case set (time histories) or a normal convention (breakaway sweeps). Every
quantity is computed from the netCDF results only.

Status of an entry: "reproduced" (with the primary variant: Table 1 as printed, or the
consistent signed normals), "reproduced with <variant>" (only with another variant, e.g. the
reported inputs), or "not reproduced" with the reason. An entry fails the validation when a
variant it expects does not reproduce it.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np
import yaml

UNITS = {"m": 1.0, "cm": 1e2, "mm": 1e3, "um": 1e6, "deg": 1.0, "cm/s": 1e2, "1": 1.0, "bool": 1.0}
CASE_KINDS = set()
BREAKAWAY_KINDS = set()
QUANTITIES = {}


def quantity(kind_set):
    def register(fn):
        QUANTITIES[fn.__name__] = fn
        kind_set.add(fn.__name__)
        return fn

    return register


@dataclass
class Results:
    """Datasets by key: cases[(variant, proto, model, dt)], breakaway[(variant, proto)] (with a
    ``dXg`` dimension)."""

    cases: dict
    breakaway: dict

    def case(self, variant, prototype, model, dt):
        return self.cases[(variant, prototype, model, float(dt))]

    def sweep(self, variant, prototype, dXg):
        return self.breakaway[(variant, prototype)].sel(dXg=float(dXg))


def _step(ds, t):
    return int(np.argmin(np.abs(ds["t"].values - t)))


def _sticking_rotation(ds):
    """|theta2 at the end of sticking - theta2 at the start of the step| per step (deg)."""
    theta2 = ds["theta2"].values
    return np.abs(ds["theta2_stick"].values[1:] - theta2[:-1])


# --- time histories (variants: case sets) -------------------------------------------------------
@quantity(CASE_KINDS)
def theta2_max(r, v, prototype, model, dt):
    return float(r.case(v, prototype, model, dt)["theta2"].max())


@quantity(CASE_KINDS)
def theta2_end(r, v, prototype, model, dt):
    return float(r.case(v, prototype, model, dt)["theta2"][-1])


@quantity(CASE_KINDS)
def rise_max(r, v, prototype, model, dt):
    """Maximum rise of RB3 above its theta2 = 0 rest position (m)."""
    return float(r.case(v, prototype, model, dt)["rise"].max())


@quantity(CASE_KINDS)
def rise_end(r, v, prototype, model, dt):
    return float(r.case(v, prototype, model, dt)["rise"][-1])


@quantity(CASE_KINDS)
def interpenetration_difference(r, v, prototype, model, dt):
    """max |I_A - I_B| over the history (m) (equal to max |I_D - I_C| for symmetric pads)."""
    ds = r.case(v, prototype, model, dt)
    return float(np.abs(ds["I_A"] - ds["I_B"]).max())


@quantity(CASE_KINDS)
def velocity(r, v, prototype, model, dt, time):
    ds = r.case(v, prototype, model, dt)
    return float(ds["Xg_dot"][_step(ds, time)])


@quantity(CASE_KINDS)
def fig20_theta2(r, v, prototype, dt, time, phase):
    """theta2 of the step ending at ``time``: at its start, end of sticking or end (deg)."""
    ds = r.case(v, prototype, "stick_slip", dt)
    n = _step(ds, time)
    return float({"start": ds["theta2"][n - 1], "stick": ds["theta2_stick"][n], "end": ds["theta2"][n]}[phase])


@quantity(CASE_KINDS)
def rest_determinant(r, v, prototype, dt):
    """|C_q| of the compliant model at t_0 (m): Eq. 30 when theta2(t0) = 0."""
    return float(r.case(v, prototype, "compliant", dt)["det_Cq"][0])


@quantity(CASE_KINDS)
def eq30_printed(r, v, prototype, dt):
    """Eq. 30 as printed, 8 sin a cos^2 a (B sin a + A cos a) cos theta2, with the dataset's rest
    contact angle a and theta2(t_0) (m)."""
    return _eq30(r.case(v, prototype, "compliant", dt), +1)


@quantity(CASE_KINDS)
def eq30_corrected(r, v, prototype, dt):
    """Eq. 30 with the sign corrected, 8 sin a cos^2 a (B sin a - A cos a) cos theta2 (m)."""
    return _eq30(r.case(v, prototype, "compliant", dt), -1)


def _eq30(ds, sign):
    a = np.radians(float(ds["alpha_A"][0]))
    A, B = ds.attrs["A1_m"], ds.attrs["B_m"]
    return float(8 * np.sin(a) * np.cos(a) ** 2 * (B * np.sin(a) + sign * A * np.cos(a))
                 * np.cos(np.radians(float(ds["theta2"][0]))))


@quantity(CASE_KINDS)
def sticking_rotation_at_velocity_peak(r, v, prototype, dt):
    """|X_g_dot| at the step of the largest sticking rotation, relative to max |X_g_dot| (1)."""
    ds = r.case(v, prototype, "stick_slip", dt)
    n = int(np.argmax(_sticking_rotation(ds))) + 1
    vel = np.abs(ds["Xg_dot"].values)
    return float(vel[n] / vel.max())


@quantity(CASE_KINDS)
def sticking_rotation_ratio(r, v, prototype, dt, other_prototype, other_dt):
    """max sticking rotation of (prototype, dt) / that of (other_prototype, other_dt) (1)."""
    mine = _sticking_rotation(r.case(v, prototype, "stick_slip", dt)).max()
    other = _sticking_rotation(r.case(v, other_prototype, "stick_slip", other_dt)).max()
    return float(mine / other)


@quantity(CASE_KINDS)
def diagonal_endpoint_mismatch(r, v, prototype, model, dt):
    """max(|I_A - I_D|, |I_B - I_C|) over the history (m): 0 when the endpoints superimpose."""
    ds = r.case(v, prototype, model, dt)
    return float(max(np.abs(ds["I_A"] - ds["I_D"]).max(), np.abs(ds["I_B"] - ds["I_C"]).max()))


@quantity(CASE_KINDS)
def opposite_working_diagonal(r, v, prototype, dt, threshold=0.1):
    """Fraction of the steps with a working diagonal in compliant sliding (|I_B - I_A| above
    ``threshold`` times its peak) whose stick-slip jammed diagonal is the other one (1); the
    paper: 'always the opposite'."""
    comp = r.case(v, prototype, "compliant", dt)
    ss = r.case(v, prototype, "stick_slip", dt)
    d = (comp["I_B"] - comp["I_A"]).values[1:]
    working = np.abs(d) > threshold * np.abs(d).max()
    jammed_bc = ss["sticking_diagonal"].values[1:] == 1
    return float(np.mean((d[working] > 0) != jammed_bc[working]))


# --- breakaway sweeps (variants: normal conventions) ----------------------------------------------
@quantity(BREAKAWAY_KINDS)
def breakaway_difference(r, v, prototype, dXg, statistic):
    """mean or max over theta2(t0) of I_B - I_A after the first step (m)."""
    d = (r.sweep(v, prototype, dXg)["I_B"] - r.sweep(v, prototype, dXg)["I_A"]).values
    return float(getattr(np, statistic)(d))


@quantity(BREAKAWAY_KINDS)
def breakaway_endpoint_mismatch(r, v, prototype, dXg):
    ds = r.sweep(v, prototype, dXg)
    return float(max(np.abs(ds["I_A"] - ds["I_D"]).max(), np.abs(ds["I_B"] - ds["I_C"]).max()))


@quantity(BREAKAWAY_KINDS)
def breakaway_bc_larger(r, v, prototype, dXg):
    """Fraction of theta2(t0) where the B2C2 diagonal penetrates more than A2D2 (1)."""
    ds = r.sweep(v, prototype, dXg)
    return float(np.mean((ds["I_B"] - ds["I_A"]).values > 0))


@quantity(BREAKAWAY_KINDS)
def breakaway_min_determinant(r, v, prototype, dXg):
    return float(np.abs(r.sweep(v, prototype, dXg)["det_Cq"]).min())


@quantity(BREAKAWAY_KINDS)
def breakaway_scaling(r, v, prototype, dXg, other_dXg, corner):
    """mean I_corner at dXg / mean I_corner at other_dXg (1): 'almost doubles' in the paper."""
    big = r.sweep(v, prototype, dXg)[f"I_{corner}"].mean()
    small = r.sweep(v, prototype, other_dXg)[f"I_{corner}"].mean()
    return float(big / small)


# --- evaluation ---------------------------------------------------------------------------------
def load_values(path) -> list[dict]:
    entries = yaml.safe_load(open(path))["values"]
    seen = set()
    for e in entries:
        missing = {"id", "description", "source", "value", "unit", "tolerance", "quantity", "expect"} - set(e)
        if missing:
            raise ValueError(f"paper value {e.get('id', '?')!r}: missing key(s) {sorted(missing)}")
        if e["id"] in seen:
            raise ValueError(f"paper value {e['id']!r} is listed twice")
        seen.add(e["id"])
        if e["unit"] not in UNITS:
            raise ValueError(f"paper value {e['id']!r}: unit {e['unit']!r} not in {sorted(UNITS)}")
        if e["quantity"].get("kind") not in QUANTITIES:
            raise ValueError(f"paper value {e['id']!r}: unknown quantity kind {e['quantity'].get('kind')!r}; "
                             f"known: {sorted(QUANTITIES)}")
        if e.get("relation", "within") not in ("within", "greater", "less"):
            raise ValueError(f"paper value {e['id']!r}: relation must be within, greater or less")
        if not e["expect"] and not e.get("reason"):
            raise ValueError(f"paper value {e['id']!r}: a value expected not to reproduce needs a 'reason'")
    return entries


def evaluate(entries, results: Results, case_variants, breakaway_variants) -> list[dict]:
    """Compute every entry for every variant; statuses as in the module docstring."""
    rows = []
    for e in entries:
        params = dict(e["quantity"])
        kind = params.pop("kind")
        variants = case_variants if kind in CASE_KINDS else breakaway_variants
        scale = UNITS[e["unit"]]
        computed, passed = {}, []
        for v in variants:
            try:
                value = QUANTITIES[kind](results, v, **params) * scale
            except KeyError:
                continue  # this variant has no such dataset
            computed[v] = value
            if _holds(e.get("relation", "within"), value, e["value"], e["tolerance"]):
                passed.append(v)
        if passed and passed[0] == variants[0]:
            status = "reproduced"
        elif passed:
            status = "reproduced with " + ", ".join(_variant_name(v) for v in passed)
        else:
            status = "not reproduced"
        expected = list(e["expect"])
        failing = [v for v in expected if v not in passed]
        best = min(computed.values(), key=lambda x: abs(x - e["value"])) if computed else float("nan")
        rows.append({
            "id": e["id"], "description": e["description"], "source": e["source"],
            "paper_value": e["value"], "unit": e["unit"], "tolerance": e["tolerance"],
            "relation": e.get("relation", "within"),
            "computed": computed, "deviation": best - e["value"], "status": status,
            "expected": expected, "ok": not failing,
            "reason": e.get("reason", "") if status == "not reproduced" or failing else e.get("note", ""),
        })
    return rows


def _holds(relation, value, paper, tol):
    """within: |value - paper| <= tol; greater / less: value beyond paper by more than tol."""
    if relation == "within":
        return abs(value - paper) <= tol
    if relation == "greater":
        return value > paper + tol
    if relation == "less":
        return value < paper - tol
    raise ValueError(f"relation must be within, greater or less, got {relation!r}")


def _variant_name(v):
    return {"as_reported": "reported inputs", "as_printed": "Table 1 as printed",
            "unsigned": "unsigned normals", "signed": "signed normals"}.get(v, v)


def _fmt(x):
    return f"{x:.6g}" if isinstance(x, float) else str(x)


def markdown(rows, case_variants, breakaway_variants) -> str:
    variants = list(dict.fromkeys([*case_variants, *breakaway_variants]))
    head = ["id", "what", "source", "paper", "unit", "check", *variants, "status", "note"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        check = {"within": f"± {_fmt(r['tolerance'])}", "greater": "greater", "less": "less"}[r["relation"]]
        cells = [r["id"], r["description"], r["source"], _fmt(r["paper_value"]), r["unit"], check,
                 *[_fmt(r["computed"][v]) if v in r["computed"] else "" for v in variants],
                 ("**FAIL** " if not r["ok"] else "") + r["status"], r["reason"]]
        lines.append("| " + " | ".join(c.replace("|", "/") for c in cells) + " |")
    n_ok = sum(r["status"] != "not reproduced" for r in rows)
    failing = [r["id"] for r in rows if not r["ok"]]
    summary = (f"{n_ok} of {len(rows)} stated numbers reproduced; "
               + (f"FAILED (expected to reproduce, did not): {', '.join(failing)}" if failing
                  else "every number expected to reproduce does."))
    return "# Validation against the paper\n\n" + summary + "\n\n" + "\n".join(lines) + "\n"


def to_csv(rows, case_variants, breakaway_variants) -> str:
    """The table of ``markdown`` as CSV (for the Snakemake report)."""
    import csv
    import io

    variants = list(dict.fromkeys([*case_variants, *breakaway_variants]))
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["id", "what", "source", "paper", "unit", "check", *variants, "status", "note"])
    for r in rows:
        check = {"within": f"+/- {_fmt(r['tolerance'])}", "greater": "greater", "less": "less"}[r["relation"]]
        writer.writerow([r["id"], r["description"], r["source"], _fmt(r["paper_value"]), r["unit"], check,
                         *[_fmt(r["computed"][v]) if v in r["computed"] else "" for v in variants],
                         ("FAIL " if not r["ok"] else "") + r["status"], r["reason"]])
    return out.getvalue()


def to_json(rows) -> str:
    return json.dumps(rows, indent=1, sort_keys=True)
