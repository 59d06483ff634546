"""The output files read back by the tools users read them with: the Parquet tables
hold the CSV tables' numbers bit for bit (read by pyarrow), with every column's unit in
the metadata; the summary is small and the final state is a table of its own."""

import csv
import json
import subprocess

import pyarrow.parquet as pq

import cablesim

TABLES = ["end_forces", "tensions", "positions", "points", "final_state"]


def read_csv(path):
    with open(path, newline="") as f:
        r = csv.reader(f)
        header = next(r)
        cols = [[] for _ in header]
        for row in r:
            for c, v in zip(cols, row):
                c.append(v)
    return header, cols


def test_parquet_holds_the_csv_numbers(tmp_path, repo, cli):
    scenario = repo / "examples" / "buoy_spread.toml"
    sim = cablesim.Simulation.from_file(scenario, backend="cpu", duration=2.0)
    sim.run(tmp_path / "pq", format="parquet")
    # The CSV files of the same run, written by the command line.
    subprocess.run(cli + ["run", "-q", str(scenario), "--backend", "cpu",
                          "--duration", "2", "--out", str(tmp_path / "csv")],
                   check=True)
    for name in TABLES:
        header, cols = read_csv(tmp_path / "csv" / f"{name}.csv")
        path = tmp_path / "pq" / f"{name}.parquet"
        table = pq.read_table(path)
        assert table.column_names == header, name
        units = json.loads(pq.read_metadata(path).metadata[b"units"])
        assert set(units) == set(header), name
        for h, text in zip(header, cols):
            values = table.column(h).to_pylist()
            assert len(values) == len(text), f"{name}.{h}"
            if isinstance(values[0], float):
                # Bit for bit: CSV holds the shortest text of each f64.
                assert [float(x) for x in text] == values, f"{name}.{h}"
            elif isinstance(values[0], int):
                assert [int(x) for x in text] == values, f"{name}.{h}"
            else:
                assert text == values, f"{name}.{h}"
    assert units["x"] == "m" and units["vx"] == "m/s"


def test_summary_is_small_and_the_final_state_is_a_table(tmp_path, catenary_path):
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=1.0)
    summary = sim.run(tmp_path / "out", format="parquet")
    cable = summary["cables"][0]
    assert "final_positions" not in cable
    assert cable["max_tension"][0] >= cable["min_tension"]
    fin = pq.read_table(tmp_path / "out" / "final_state.parquet")
    assert fin.num_rows == len(sim.positions(0))
    assert fin.column("z").to_pylist() == [p[2] for p in sim.positions(0)]
    text = (tmp_path / "out" / "summary.json").read_text()
    assert json.loads(text)["status"] == "completed"
    assert len(text) < 2000


def test_unknown_format_is_refused(tmp_path, catenary_path):
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=1.0)
    try:
        sim.run(tmp_path / "out", format="hdf5")
    except ValueError as e:
        assert "format" in str(e) and "parquet" in str(e)
    else:
        raise AssertionError("format='hdf5' was accepted")
