"""Reading DMA CSV files: units from the header, E = 3 G, isotherm grouping, and one
clear error (file, line or column, value, rule) for each kind of bad input."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bem.dma import DMAData, DMAInputError, Isotherm, read_dma_csv

REPO = Path(__file__).resolve().parents[3]
EXAMPLE = REPO / "examples" / "data" / "dma-pyvisco-freq-raw.csv"


def _csv(tmp_path, text: str, name: str = "dma.csv") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


GOOD = """# two isotherms
temperature_degC,frequency_hz,G_storage_MPa,G_loss_MPa
20,0.1,1.0,0.1
20,1.0,1.5,0.2
20,10,2.0,0.3
30.2,0.1,0.8,0.08
30.1,1.0,1.2,0.15
30.0,10,1.6,0.25
"""


def test_units_from_the_header_are_converted_to_SI(tmp_path):
    data = read_dma_csv(_csv(tmp_path, GOOD))
    assert len(data.isotherms) == 2
    cold, hot = data.isotherms
    assert cold.temperature == pytest.approx(293.15)
    assert hot.temperature == pytest.approx(273.15 + 30.1)  # the mean of its rows
    np.testing.assert_allclose(cold.omega, 2 * math.pi * np.array([0.1, 1.0, 10.0]))
    np.testing.assert_allclose(cold.storage, [1e6, 1.5e6, 2e6])
    np.testing.assert_allclose(cold.loss, [1e5, 2e5, 3e5])


def test_tensile_moduli_are_divided_by_three_and_kelvin_and_rad_s_are_kept(tmp_path):
    text = "temperature_K,omega_rad_s,E_storage_Pa,E_loss_Pa\n300,1,3e6,3e5\n300,2,6e6,6e5\n"
    (iso,) = read_dma_csv(_csv(tmp_path, text)).isotherms
    assert iso.temperature == 300.0
    np.testing.assert_allclose(iso.omega, [1.0, 2.0])
    np.testing.assert_allclose(iso.storage, [1e6, 2e6])  # G = E / 3 (incompressible)
    np.testing.assert_allclose(iso.loss, [1e5, 2e5])


def test_units_by_argument_and_decreasing_sweeps(tmp_path):
    text = "temperature,frequency,G_storage,G_loss\n25,10,2,0.2\n25,1,1,0.1\n"
    (iso,) = read_dma_csv(_csv(tmp_path, text), temperature_unit="degC", frequency_unit="Hz",
                          modulus_unit="kPa").isotherms
    np.testing.assert_allclose(iso.omega, 2 * math.pi * np.array([1.0, 10.0]))  # sorted
    np.testing.assert_allclose(iso.storage, [1e3, 2e3])


def test_isotherm_column_groups_rows(tmp_path):
    text = "isotherm,temperature_degC,frequency_hz,G_storage_Pa,G_loss_Pa\n" \
           "a,20,1,1,0\na,20,2,2,0\nb,20.5,1,1,0\nb,20.5,2,2,0\n"
    assert len(read_dma_csv(_csv(tmp_path, text)).isotherms) == 2


def test_shipped_example_reads_as_21_isotherms():
    data = read_dma_csv(EXAMPLE)
    assert len(data.isotherms) == 21
    assert data.temperatures[0] - 273.15 == pytest.approx(-49.9, abs=0.1)
    assert data.temperatures[-1] - 273.15 == pytest.approx(100.0, abs=0.1)
    # first row: 0.1 Hz, E' = 8097.175545 MPa
    assert data.isotherms[0].storage[0] == pytest.approx(8097.175545e6 / 3)
    assert data.isotherms[0].omega[0] == pytest.approx(0.2 * math.pi)


@pytest.mark.parametrize("header, missing", [
    ("frequency_hz,G_storage_Pa,G_loss_Pa", "temperature_degC or temperature_K"),
    ("temperature_K,G_storage_Pa,G_loss_Pa", "frequency_hz or omega_rad_s"),
    ("temperature_K,frequency_hz,G_loss_Pa", "G_storage_<unit> or E_storage_<unit>"),
    ("temperature_K,frequency_hz,E_storage_Pa", "E_loss_<unit>"),
])
def test_missing_column_names_the_file_and_the_column(tmp_path, header, missing):
    path = _csv(tmp_path, header + "\n" + ",".join(["1"] * len(header.split(","))) + "\n")
    with pytest.raises(DMAInputError) as err:
        read_dma_csv(path)
    assert str(path) in str(err.value) and "missing column" in str(err.value) and missing in str(err.value)
    assert "columns found:" in str(err.value)


def test_column_without_unit_and_no_argument(tmp_path):
    path = _csv(tmp_path, "temperature_K,frequency,G_storage_Pa,G_loss_Pa\n300,1,1,1\n")
    pattern = r"column 'frequency' has no unit.*frequency_hz or omega_rad_s.*frequency_unit"
    with pytest.raises(DMAInputError, match=pattern):
        read_dma_csv(path)


def test_header_and_argument_units_must_agree(tmp_path):
    path = _csv(tmp_path, GOOD)
    with pytest.raises(DMAInputError, match=r"column 'frequency_hz' says 'hz' but frequency_unit='rad/s'"):
        read_dma_csv(path, frequency_unit="rad/s")


def test_shear_and_tensile_together_are_ambiguous(tmp_path):
    path = _csv(tmp_path, "temperature_K,frequency_hz,G_storage_Pa,E_loss_Pa\n300,1,1,1\n")
    with pytest.raises(DMAInputError, match="not both"):
        read_dma_csv(path)


def test_non_monotonic_frequencies_name_the_line_and_values(tmp_path):
    text = GOOD.replace("20,10,2.0,0.3", "20,0.5,2.0,0.3")
    path = _csv(tmp_path, text)
    with pytest.raises(DMAInputError) as err:
        read_dma_csv(path)
    msg = str(err.value)
    assert f"{path} line 5" in msg and "strictly monotonic" in msg and "293.15 K" in msg
    assert repr(2 * math.pi * 0.5) in msg and repr(2 * math.pi * 1.0) in msg


@pytest.mark.parametrize("row, pattern", [
    ("20,10,-2.0,0.3", r"line 5, column 'G_storage_MPa': storage modulus must be > 0, got '-2.0'"),
    ("20,10,0,0.3", r"line 5, column 'G_storage_MPa': storage modulus must be > 0, got '0'"),
    ("20,10,2.0,-0.3", r"line 5, column 'G_loss_MPa': loss modulus must be >= 0, got '-0.3'"),
    ("20,10,nan,0.3", r"line 5, column 'G_storage_MPa': must be finite, got 'nan'"),
    ("20,10,2.0,inf", r"line 5, column 'G_loss_MPa': must be finite, got 'inf'"),
    ("20,10,2.0,abc", r"line 5, column 'G_loss_MPa': not a number: 'abc'"),
    ("-300,10,2.0,0.3", r"line 5: temperature must be > 0 K"),
    ("20,10,2.0", r"line 5: expected 4 columns, got 3"),
])
def test_bad_values_name_file_line_column_value_and_rule(tmp_path, row, pattern):
    path = _csv(tmp_path, GOOD.replace("20,10,2.0,0.3", row))
    with pytest.raises(DMAInputError, match=pattern) as err:
        read_dma_csv(path)
    assert str(err.value).startswith(str(path))


def test_an_isotherm_of_one_row_is_refused(tmp_path):
    path = _csv(tmp_path, GOOD + "40,1,1,0.1\n")
    with pytest.raises(DMAInputError, match=r"line 9: the isotherm at 313.15 K has 1 row"):
        read_dma_csv(path)


def test_arrays_are_checked_like_files():
    with pytest.raises(DMAInputError, match=r"isotherm at 300.0 K, point 1: loss modulus must be >= 0 Pa, got -1.0"):
        DMAData.from_arrays([300.0], [[1.0, 2.0]], [[1.0, 1.0]], [[1.0, -1.0]])
    with pytest.raises(DMAInputError, match=r"point 1: storage modulus must be finite \(Pa\), got nan"):
        Isotherm(300.0, [1.0, 2.0], [1.0, math.nan], [0.0, 0.0])
    with pytest.raises(DMAInputError, match=r"point 2: frequencies within an isotherm must be strictly monotonic"):
        Isotherm(300.0, [1.0, 2.0, 1.5], [1.0, 1.0, 1.0], [0.0, 0.0, 0.0])
    with pytest.raises(DMAInputError, match="temperature must be a finite number > 0 K"):
        Isotherm(-1.0, [1.0, 2.0], [1.0, 1.0], [0.0, 0.0])


def test_a_byte_order_mark_is_not_part_of_the_first_column_name(tmp_path):
    path = tmp_path / "bom.csv"
    path.write_text("temperature_K,omega_rad_s,G_storage_Pa,G_loss_Pa\n300,1,1,0\n300,2,2,0\n", encoding="utf-8-sig")
    (iso,) = read_dma_csv(path).isotherms
    assert iso.temperature == 300.0
