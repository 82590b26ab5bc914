"""Bad ``[material] model = "dma"`` input through ``bem solve``: exit status 2 and a
message that names the file, the line or the key."""

from __future__ import annotations

import pytest

import casefile
from bem.cli import main
from bem.dma import DMAData

HEADER = "temperature_degC,frequency_hz,G_storage_MPa,G_loss_MPa\n"


def _solve(kit, material, capsys, csv_text=None, speed=0.01) -> str:
    if csv_text is not None:
        (kit.folder / "bad.csv").write_text(csv_text)
        material = {**material, "file": "bad.csv"}
    path = kit.write(kit.case(material, speed))
    assert main(["solve", str(path), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bem: error: ") and "Traceback" not in err
    return err


@pytest.mark.parametrize("csv_text, message", [
    (HEADER.replace(",G_loss_MPa", "") + "20,1,1\n20,2,1.1\n",
     "missing column G_loss_<unit> or E_loss_<unit> (columns found: temperature_degC, frequency_hz, G_storage_MPa)"),
    (HEADER + "20,1,1,0.1\n20,2,1.1,0.1\n20,1.5,1.2,0.1\n30,1,1,0.1\n30,2,1.1,0.1\n",
     "bad.csv line 4: frequencies within an isotherm (isotherm at 293.15 K) must be strictly monotonic, "
     "got 9.42"),
    (HEADER + "20,1,1,0.1\n20,2,1.1,-0.1\n",
     "bad.csv line 3, column 'G_loss_MPa': loss modulus must be >= 0, got '-0.1'"),
    (HEADER + "20,1,-1,0.1\n20,2,1.1,0.1\n", "bad.csv line 2, column 'G_storage_MPa': storage modulus must be > 0"),
])
def test_a_bad_dma_file_exits_2_naming_the_file_and_line(kit, capsys, csv_text, message):
    err = _solve(kit, kit.material(), capsys, csv_text)
    assert message in err
    assert "bad.csv" in err


def test_a_single_isotherm_where_shifting_is_asked(kit, capsys):
    err = _solve(kit, kit.material(), capsys, HEADER + "20,1,1,0.1\n20,2,1.1,0.1\n20,4,1.2,0.1\n")
    assert 'shift_law = "wlf" (fitted), reference_temperature = 293.15 K: ' in err
    assert "bad.csv: shifting needs at least 2 isotherms, got 1 (at 293.15 K)" in err


def test_a_temperature_at_or_below_the_wlf_singularity(kit, capsys):
    # T_ref - C2 = 293.15 - 50 = 243.15 K
    for T in (243.0, 230.0):
        err = _solve(kit, kit.material(C1=8.86, C2=50.0, temperature=T), capsys)
        assert f"[material] model = \"dma\": temperature = {T!r} K" in err
        assert "at or below the WLF singularity T_ref - C2 = 293.15 - 50 = 243.15 K" in err
    # at the singularity to round-off (293.15 - 50 is 243.14999999999998 in floating point)
    err = _solve(kit, kit.material(C1=8.86, C2=50.0, temperature=243.15), capsys)
    assert "temperature = 243.15 K" in err and "WLF law is singular at T_ref - C2 = 243.15 K" in err


def test_a_prony_fit_that_cannot_reach_the_stated_tolerance(kit, capsys):
    err = _solve(kit, kit.material(fit_tolerance=1e-9, terms_per_decade=0.5), capsys)
    assert "fit_tolerance = 1e-09, terms_per_decade = 0.5" in err
    assert "the Prony fit cannot reach tolerance = 1e-09: max relative error of G' is" in err
    assert "dma.csv" in err


def test_a_band_outside_the_data_exits_2_until_extrapolate_is_set(kit, capsys):
    err = _solve(kit, kit.material(), capsys, speed=2e-6)
    assert "decades below" in err and "[material] extrapolate = true" in err
    path = kit.write(kit.case(kit.material(extrapolate=True), 2e-6))
    assert main(["solve", str(path), "--quiet"]) == 0


@pytest.mark.parametrize("keys, message", [
    ({"C1": 8.86}, "C1 = 8.86 is given without C2; give both WLF constants, or neither"),
    ({"shift_law": "arrhenius", "C2": 50.0}, 'C2 belong to shift_law = "wlf", got shift_law = "arrhenius"'),
    ({"activation_energy": 1.5e5}, 'activation_energy belongs to shift_law = "arrhenius"'),
    ({"form": "table", "terms_per_decade": 3.0}, 'terms_per_decade apply only to form = "prony", got form = "table"'),
    ({"temperatur": 300.0}, "unknown key 'temperatur' for model = \"dma\""),
    ({"temperature": -5.0}, "[material] temperature must be > 0 K, got -5.0"),
    ({"vertical": "density"}, 'vertical = "density" needs a density_kg_m3 column in '),
    ({"shift_law": "vft"}, '[material] shift_law must be one of "wlf", "arrhenius", got \'vft\''),
])
def test_key_errors_name_the_key(kit, capsys, keys, message):
    assert message in _solve(kit, kit.material(**keys), capsys)


def test_fem_reference_refuses_dma_and_says_what_to_do(kit):
    path = kit.write(kit.case(kit.material()))
    with pytest.raises(casefile.CaseFileError, match='fem-reference solve cannot solve \\[material\\] model = "dma"'):
        casefile.read(path, tool="fem")


def test_single_isotherm_with_a_given_law_runs(kit, synthetic):
    """Shifting by a given law needs no second isotherm."""
    one = synthetic(kit.law, [kit.T_REF])
    assert isinstance(one, DMAData) and len(one.isotherms) == 1
    kit.write_csv(kit.folder / "one.csv", one)
    path = kit.write(kit.case({**kit.material(C1=8.86, C2=101.6), "file": "one.csv"}, 0.01))
    assert main(["solve", str(path), "--quiet"]) == 0
