"""The claims table: status rules on made-up rows, the bounds the studies use, and (slow) that the
claims follow the workflow's outputs and that each study reruns on its own config only."""

import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from rotbeam.config.errors import RotbeamInputError
from rotbeam.config.scenefile import load_yaml
from rotbeam.model.params import BETA1, Beam
from rotbeam.paper.claims import agrees, c_hypotheses_long, judge
from rotbeam.paper.collapse import southwell_delta
from rotbeam.paper.hypotheses import single_change_study
from rotbeam.paper.printed import load_claims
from rotbeam.paper.studies import convergence_lines, fig7_beams, grid_beam, grid_columns

ROOT = Path(__file__).resolve().parents[1]
CLAIMS = ROOT / "rotbeam/paper/paper_claims.yaml"
TARGET = "results/reproduction/claims.csv"
# the target first: --configfile takes every word after it
SNAKEMAKE = [sys.executable, "-m", "snakemake", TARGET]


def rows(*specs):
    keys = ("id", "source", "paper", "unit", "tolerance", "kind")
    return pd.DataFrame([dict(zip(keys, s, strict=True)) for s in specs])


def hyps(*specs):
    return pd.DataFrame(specs, columns=["claim", "hypothesis", "value", "note"])


def test_status_rules_on_made_up_rows():
    claims = rows(
        ("a", "s", 6.37, "Hz", 0.005, "rounding"),
        ("b", "s", 0.385, "", 0.001, "stated"),
        ("c", "s", 0.385, "", 0.001, "stated"),
        ("d", "s", 0.10, "", 0, "below"),
        ("e", "s", 1, "", 0, "exact"),
    )
    ours = {"a": (6.374, ""), "b": (0.354, ""), "c": (0.354, ""), "d": (0.125, ""),
            "e": (math.nan, "")}  # fmt: skip
    h = hyps(
        ("b", "far", 0.30, ""), ("b", "near", 0.3855, "x"),
        ("c", "one", 0.36, ""), ("c", "two", 0.39, ""),
        ("d", "reading", 0.03, ""),
    )  # fmt: skip
    t = judge(claims, ours, h).set_index("id")
    assert t.loc["a", "status"] == "reproduced" and "rounding" in t.loc["a", "explanation"]
    assert t.loc["b", "status"] == "explained" and t.loc["b", "explained_value"] == 0.3855
    assert "near" in t.loc["b", "explanation"] and "far gave 0.3" in t.loc["b", "explanation"]
    assert t.loc["c", "status"] == "unexplained" and math.isnan(t.loc["c", "explained_value"])
    assert (
        "one gave 0.36" in t.loc["c", "explanation"]
        and "two gave 0.39" in t.loc["c", "explanation"]
    )
    assert t.loc["d", "status"] == "explained"  # the reading puts it on the claimed side
    assert t.loc["e", "status"] == "unexplained"  # NaN never reproduces
    assert list(t.reset_index().columns) == ["id", "source", "paper", "ours", "unit", "status",
                                             "explained_value", "explanation"]  # fmt: skip


def test_band_edges_and_kinds():
    assert agrees(0.31623, 0.3162, 0.00005, "rounding")
    assert not agrees(0.3163, 0.3162, 0.00005, "rounding")
    assert agrees(0.10, 0.10, 0, "at_least") and not agrees(0.10, 0.10, 0, "below")
    assert agrees(20, 40, 0, "at_most") and not agrees(80, 40, 0, "at_most")


def test_claims_file_is_complete_and_checked():
    inputs, claims = load_claims(load_yaml(CLAIMS.read_text()))
    need = {"f_n_hz", "zeta", "resonance_omega5_hz", "c_0.05", "c_0.07", "c_0.10", "c_0.12",
            "c_fig7", "E_star_plateau", "E_star_exponent", "fig5_50_2", "fig5_50_1",
            "fig7_collapse", "c0_0.02", "c0_0.04", "c0_0.06", "c0_0.08", "c0_0.10",
            "N_converged", "figD9_range"}  # fmt: skip
    assert need <= set(claims["id"])
    assert {"E", "gamma", "L", "h", "rho", "beta1"} <= set(inputs)
    bad = {"claims": [{"id": "x", "source": "s", "paper": 1, "unit": "", "tolerance": 0,
                       "kind": "roughly"}]}  # fmt: skip
    with pytest.raises(RotbeamInputError, match="kind = 'roughly'"):
        load_claims(bad)


def test_c_hypotheses_slot_names_the_claims():
    t = c_hypotheses_long(pd.DataFrame({"hypothesis": ["h"], "threshold": [0.1], "c": [0.38]}))
    assert t["claim"].tolist() == ["c_0.10"]


def test_c_claims_need_one_mechanism_at_every_threshold():
    """A c hypothesis that hits one threshold but misses another explains neither (App. D's
    four values come from one pipeline); one that hits both explains both."""
    claims = rows(("c_0.05", "D", 0.311, "", 0.001, "stated"),
                  ("c_0.10", "D", 0.385, "", 0.001, "stated"))  # fmt: skip
    study = pd.DataFrame({"hypothesis": ["knob", "knob", "pipeline", "pipeline"],
                          "threshold": [0.05, 0.10, 0.05, 0.10],
                          "c": [0.3112, 0.3700, 0.3105, 0.3853]})  # fmt: skip
    ours = {"c_0.05": (0.229, ""), "c_0.10": (0.323, "")}
    long = c_hypotheses_long(study, claims)
    assert long.set_index("hypothesis")["counts"].groupby(level=0).all().to_dict() == {
        "knob": False, "pipeline": True}  # fmt: skip
    out = judge(claims, ours, long).set_index("id")
    assert (out["status"] == "explained").all()
    assert "pipeline gives" in out.loc["c_0.05", "explanation"]
    assert "knob gave 0.3112 (misses c_0.10)" in out.loc["c_0.05", "explanation"]
    alone = judge(claims, ours, long[long["hypothesis"] == "knob"]).set_index("id")
    assert (alone["status"] == "unexplained").all()


def test_southwell_delta_limits():
    # delta = 1 (clamp on the axis): the classical hub-free Southwell coefficient 1.1933 of
    # flapwise bending, less the 1 of in-plane softening
    assert southwell_delta(1 - 1e-12) == pytest.approx(1.1933 - 1.0, abs=5e-4)
    d = np.logspace(-6, np.log10(0.999), 300)
    v = np.array([southwell_delta(x) for x in d])
    assert v.max() < 1.6 and (np.diff(v) < 0).all()  # bounded, largest far from the axis


def test_single_change_gives_the_target():
    inputs, _ = load_claims(load_yaml(CLAIMS.read_text()))
    beam = Beam()
    t, _ = single_change_study(beam, inputs, 6.37, 0.017)
    row = t[(t["target"] == "f_n") & (t["input"] == "L")].iloc[0]
    # rebuild the beam from scratch: Eq. (natural_freq) at the changed L
    assert Beam(L=row["needed"]).f_n == pytest.approx(6.37, rel=1e-12)
    g = t[(t["target"] == "zeta") & (t["input"] == "gamma")].iloc[0]
    assert Beam(gamma=g["needed"]).zeta == pytest.approx(0.017, rel=1e-12)
    assert not t.loc[t["target"] != "both", "gives_both"].any()


def test_grid_beam_keeps_what_it_says():
    ref = Beam().__dict__
    for E, L in ((1e5, 1e-4), (1e9, 1e-2)):
        eta = Beam(**grid_beam(ref, E, L, 0.05, "eta", "delta"))
        assert eta.eta == pytest.approx(Beam().eta) and eta.delta == pytest.approx(Beam().delta)
        z = Beam(**grid_beam(ref, E, L, 0.05, "zeta", "R", zeta=0.017))
        assert z.zeta == pytest.approx(0.017) and z.R == Beam().R
        assert z.eta == pytest.approx(2 * BETA1**2 * 0.017)


def test_grid_columns_and_convergence_lines_of_the_config():
    """One sweep job per (E, L) column of the Fig. 7 grid writes each of its beams' files; one
    job runs Fig. B.8's lines, N outer and Omega_0 inner."""
    config = load_yaml((ROOT / "config/config.yaml").read_text())
    f7, beams = config["fig7"], fig7_beams(config)
    columns, tails = grid_columns(beams)
    assert len(columns) == len(f7["E"]) * len(f7["L"]) and len(tails) == len(f7["h_over_L"])
    assert {c + t for c in columns for t in tails} == set(beams)
    assert {b: beam for col in columns.values() for b, beam in col.items()} == beams
    assert columns["E1e+07_L0.0001"]["E1e+07_L0.0001_hL0.05"]["h"] == pytest.approx(5e-6)
    tagged = fig7_beams({**config, "fig7": {**f7, "damping": "eta", "geometry": "delta"}})
    assert grid_columns(tagged)[1] == [t + "_eta-delta" for t in tails]
    cv = config["convergence"]
    lines = convergence_lines(config)
    assert list(lines) == [f"conv_N{n}_w{w:g}" for n in cv["N"] for w in cv["omega0"]]
    assert all(s["beam"] == config["beam"] and s["f_d"] == cv["f_d"] for s in lines.values())


# --- through snakemake (slow) -----------------------------------------------------------------


@pytest.fixture(scope="module")
def claims_work(quick_run, tmp_path_factory) -> Path:
    """A copy of the session's finished quick run (conftest), results and records included:
    these tests edit outputs and config, so they must not touch the shared run."""
    work = tmp_path_factory.mktemp("claims") / "wf"
    shutil.copytree(quick_run, work, symlinks=True)
    return work


def dry_jobs(work: Path, *extra: str) -> dict[str, int]:
    p = subprocess.run([*SNAKEMAKE, "-n", "--cores", "1", "--configfile", "config/quick.yaml",
                        *extra], cwd=work, capture_output=True, text=True, timeout=300)  # fmt: skip
    assert p.returncode == 0, p.stderr[-3000:]
    jobs, stats = {}, False
    for line in p.stdout.splitlines():
        if line.startswith("job ") and "count" in line:
            stats = True
            continue
        if stats:
            parts = line.split()
            if not parts or parts[0] == "total":
                break
            if not parts[0].startswith("---"):
                jobs[parts[0]] = int(parts[1])
    return jobs


def claims_of(work: Path, *extra: str) -> pd.DataFrame:
    p = subprocess.run([*SNAKEMAKE, "--cores", "1", "--configfile", "config/quick.yaml",
                        *extra], cwd=work, capture_output=True, text=True, timeout=600)  # fmt: skip
    assert p.returncode == 0, p.stderr[-3000:]
    return pd.read_csv(work / "results/reproduction/claims.csv").set_index("id")


@pytest.mark.slow
def test_each_study_reruns_on_its_own_config_only(claims_work):
    assert dry_jobs(claims_work) == {}
    d9 = dry_jobs(claims_work, "--config", "reproduction={'figD9': {'delta_points': 60}}")
    assert set(d9) == {"repro_figD9", "reproduction"}, d9
    f7 = dry_jobs(claims_work, "--config", "reproduction={'fig7': {'points': 6}}")
    assert f7.get("repro_fig7_variant") == 6 and f7.get("repro_fig7") == 1, f7
    assert not {"repro_figD9", "repro_estar", "repro_fn_zeta", "sweep_line"} & set(f7), f7
    one = dry_jobs(claims_work, "--config", "reproduction={'fig7': {'damping': ['eta']}}")
    assert "repro_fig7_variant" not in one and one.get("repro_fig7") == 1, one  # reused
    beam = dry_jobs(claims_work, "--config", "beam={'gamma': 0.03}")
    assert beam.get("repro_fn_zeta") == 1 and beam.get("repro_fig7_variant") == 6, beam


@pytest.mark.slow
def test_claims_follow_the_outputs(claims_work):
    before = pd.read_csv(claims_work / "results/reproduction/claims.csv").set_index("id")
    assert before.loc["c0_0.02", "status"] == "reproduced"
    path = claims_work / "results/tables/c0_threshold.csv"
    t = pd.read_csv(path)
    t.loc[np.isclose(t["threshold"], 0.02), "c0_zeta0"] = 0.15
    t.to_csv(path, index=False)
    after = claims_of(claims_work)
    assert after.loc["c0_0.02", "ours"] == pytest.approx(0.15)
    assert after.loc["c0_0.02", "status"] == "unexplained"
    # the c study's slot: a hypothesis that gives the printed c explains the claim
    (claims_work / "results/reproduction/c_hypotheses.csv").write_text(
        "hypothesis,threshold,c\nmade-up reading,0.10,0.3851\nother,0.10,0.2\n"
    )
    slot = claims_of(claims_work, "--config", "reproduction={'c_hypotheses': True}")
    assert slot.loc["c_0.10", "status"] == "explained"
    assert slot.loc["c_0.10", "explained_value"] == pytest.approx(0.3851)
    assert "other gave 0.2" in slot.loc["c_0.10", "explanation"]
