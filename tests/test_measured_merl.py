"""MERL tables: exact file format, the index definition, lookups and bad input."""

from __future__ import annotations

import math
import struct

import numpy as np
import pytest

from lab.cli import main
from lab.measured import merl
from lab.measured.merl import MerlFormatError, MerlTable, read_merl, write_merl

DEG = math.pi / 180.0


def small_table(seed: int = 0, dims=(6, 5, 8)) -> MerlTable:
    raw = np.random.default_rng(seed).random((3, *dims)) * 1000.0
    raw[1, 2, 3, 4] = -1.0  # not measured
    return MerlTable(raw)


def test_file_layout_and_byte_identical_round_trip(tmp_path):
    table = small_table()
    first = write_merl(table, tmp_path / "a.binary")
    data = first.read_bytes()
    assert struct.unpack("<3i", data[:12]) == (6, 5, 8)
    assert len(data) == 12 + 3 * 8 * 6 * 5 * 8
    # Channel-major, then theta_h, theta_d, phi_d (phi_d fastest).
    offset = 12 + 8 * (1 * 240 + 2 * 40 + 3 * 8 + 4)
    assert struct.unpack("<d", data[offset : offset + 8])[0] == -1.0
    again = read_merl(first)
    write_merl(again, tmp_path / "b.binary")
    assert (tmp_path / "b.binary").read_bytes() == data
    assert not again.measured()[2, 3, 4] and again.measured().sum() == 6 * 5 * 8 - 1


def test_scale_factors_per_channel():
    table = MerlTable(np.ones((3, 2, 2, 2)))
    assert np.allclose(table.rgb[0, 0, 0], [1 / 1500, 1.15 / 1500, 1.66 / 1500])
    assert np.allclose(MerlTable.from_rgb(table.rgb).raw, table.raw)


@pytest.mark.parametrize(
    ("theta_h", "theta_d", "phi_d", "expected"),
    [
        (0.0, 0.0, 0.0, (0, 0, 0)),
        (1e-6, 0.5, 0.5, (0, 0, 0)),  # theta_h near 0: sqrt(1e-6 / 90) * 90 = 0.0095
        ((10 / 90) ** 2 * 90 + 1e-6, 45.2, 90.0, (10, 45, 90)),  # sqrt spacing: bin 10 starts
        ((10 / 90) ** 2 * 90 - 1e-6, 44.99, 89.99, (9, 44, 89)),
        (45.0, 89.99, 179.99, (63, 89, 179)),  # floor(sqrt(0.5) * 90) = 63
        (90.0, 90.0, 180.0, (89, 89, 179)),  # upper ends clamp into the last bin
        (-1.0, 30.0, -10.0, (0, 30, 170)),  # phi_d < 0 folds by +180 deg (L and V swapped)
        (20.0, 30.0, -179.5, (42, 30, 0)),  # sqrt(20 / 90) * 90 = 42.4
    ],
)
def test_indexing_at_hand_computed_angles(theta_h, theta_d, phi_d, expected):
    index = merl.bin_index(theta_h * DEG, theta_d * DEG, phi_d * DEG)
    assert tuple(int(i) for i in index) == expected


def test_half_diff_angles_of_simple_configurations():
    t = 30 * DEG
    L = np.array([[math.sin(t), 0, math.cos(t)], [math.sin(t), 0, math.cos(t)]])
    V = np.array([[-math.sin(t), 0, math.cos(t)], [math.sin(t), 0, math.cos(t)]])
    th, td, pd = merl.half_diff(L, V)
    assert np.allclose(th, [0, t]) and np.allclose(td, [t, 0], atol=1e-7)
    # Swapping L and V moves phi_d by 180 deg: the same bin.
    rng = np.random.default_rng(1)
    L, V = merl.directions(rng.uniform(0, 1.5, 50), rng.uniform(0, 1.5, 50), rng.uniform(-3, 3, 50))
    assert np.array_equal(
        np.stack(merl.bin_index(*merl.half_diff(L, V))),
        np.stack(merl.bin_index(*merl.half_diff(V, L))),
    )


def test_directions_invert_half_diff():
    rng = np.random.default_rng(2)
    th, td, pd = rng.uniform(0.01, 1.5, 200), rng.uniform(0.01, 1.5, 200), rng.uniform(-3, 3, 200)
    back = merl.half_diff(*merl.directions(th, td, pd))
    assert np.allclose(back[0], th) and np.allclose(back[1], td) and np.allclose(back[2], pd)


def test_linear_lookup_hits_bin_centres_exactly():
    table = MerlTable(np.abs(small_table().raw))
    dims = table.dims
    L, V = merl.bin_grid(dims)
    expected = table.rgb.reshape(-1, 3)
    above = (L[:, 2] > 0) & (V[:, 2] > 0)
    for kind in ("nearest", "linear"):
        got = merl.lookup(table, L, V, kind)
        assert np.allclose(got[above], expected[above], rtol=1e-9)
        assert np.all(got[~above] == 0)


def test_bad_files_give_clear_errors(tmp_path):
    good = write_merl(small_table(), tmp_path / "good.binary").read_bytes()
    cases = {
        "empty": b"",
        "truncated": good[:-5],
        "extra": good + b"\0" * 8,
        "negative_dims": struct.pack("<3i", 90, -90, 180) + good[12:],
        "big_endian": struct.pack(">3i", 6, 5, 8) + good[12:],
        "wrong_dims": struct.pack("<3i", 6, 5, 9) + good[12:],
    }
    nan = bytearray(good)
    nan[12 + 8 * 7 : 12 + 8 * 8] = struct.pack("<d", float("nan"))
    cases["nan"] = bytes(nan)
    words = {
        "empty": "too short",
        "truncated": "truncated",
        "extra": "extra bytes",
        "negative_dims": "dimensions",
        "big_endian": "dimensions",
        "wrong_dims": "dimensions (6, 5, 9)",
        "nan": "NaN",
    }
    for name, data in cases.items():
        path = tmp_path / f"{name}.binary"
        path.write_bytes(data)
        with pytest.raises(MerlFormatError) as err:
            read_merl(path)
        assert path.name in str(err.value) and words[name] in str(err.value), name
    with pytest.raises(MerlFormatError, match="phi_d 7"):
        read_merl(tmp_path / "nan.binary")


def test_cli_reports_bad_table_in_one_line(tmp_path, capsys):
    path = tmp_path / "short.binary"
    path.write_bytes(struct.pack("<3i", 90, 90, 180) + b"\0" * 100)
    assert main(["fit", str(path), "--no-figure"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "truncated" in err and "short.binary" in err
    assert (
        main(["render-measured", str(tmp_path / "missing.binary"), "-o", str(tmp_path / "x.png")])
        == 2
    )
    assert "no such file" in capsys.readouterr().err
