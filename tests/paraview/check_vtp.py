"""Reads pdamp's VTK XML snapshots back with the `vtk` Python package (what ParaView uses) and
checks counts, arrays and time values.

Usage: python3 check_vtp.py PDAMP_BINARY WORKDIR
Runs a short DEM simulation (data/scenes/thesis_b_soft.toml, 40 grains, snapshots every 0.01 s
for 0.02 s) and checks:
  - grains.pvd lists 3 data sets with times 0, 0.01, 0.02 s and they open through
    vtkPVDReader-like parsing (vtkXMLPolyDataReader on each file);
  - each grains_NNNNNN.vtp has 40 points and 40 vertices, point arrays id (0..39), radius
    (all 3 mm in scene B), velocity, angular_velocity and force with 3 components;
  - the positions and velocities equal the CSV snapshot of the same instant to print precision;
  - each box_NNNNNN.vtp is the container: 8 points, 6 polygons, bounds [0, Lx] × [0, Ly] ×
    [z_floor, z_floor + Lz] with Lx = Ly = 0.03675 m, Lz = 0.1225 m.
"""
import csv
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import vtk
from vtk.util.numpy_support import vtk_to_numpy
import numpy as np

binary, work = sys.argv[1], Path(sys.argv[2])
snaps = work / "o" / "snapshots"  # the default damper.snapshot_dir, under the run's directory
subprocess.run(
    [binary, "simulate", "data/scenes/thesis_b_soft.toml", "--out", str(work / "o"),
     "--set", "run.duration=0.02", "--set", "damper.count=40",
     "--set", "damper.snapshot_interval=0.01",
     "--set", "damper.snapshot_format=\"both\""],
    check=True,
)

for part in ("grains", "box"):
    root = ET.parse(snaps / f"{part}.pvd").getroot()
    sets = root.findall("./Collection/DataSet")
    times = [float(d.get("timestep")) for d in sets]
    assert len(sets) == 3, (part, len(sets))
    assert np.allclose(times, [0.0, 0.01, 0.02], atol=1e-9), times
    for k, d in enumerate(sets):
        assert d.get("file") == f"{part}_{k:06d}.vtp", d.get("file")

for k in range(3):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(str(snaps / f"grains_{k:06d}.vtp"))
    r.Update()
    pd = r.GetOutput()
    assert pd.GetNumberOfPoints() == 40, pd.GetNumberOfPoints()
    assert pd.GetNumberOfVerts() == 40, pd.GetNumberOfVerts()
    data = pd.GetPointData()
    arrays = {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}
    assert set(arrays) == {"id", "radius", "velocity", "angular_velocity", "force"}, set(arrays)
    assert list(arrays["id"]) == list(range(40))
    assert np.allclose(arrays["radius"], 0.003), arrays["radius"][:3]
    for name in ("velocity", "angular_velocity", "force"):
        assert arrays[name].shape == (40, 3), (name, arrays[name].shape)
    pos = vtk_to_numpy(pd.GetPoints().GetData())
    with open(snaps / f"grains_{k:06d}.csv") as f:
        rows = list(csv.DictReader(f))
    ref_pos = np.array([[float(r["x_m"]), float(r["y_m"]), float(r["z_m"])] for r in rows])
    ref_vel = np.array([[float(r["vx_m_s"]), float(r["vy_m_s"]), float(r["vz_m_s"])] for r in rows])
    assert np.allclose(pos, ref_pos, rtol=1e-12, atol=1e-15), np.abs(pos - ref_pos).max()
    assert np.allclose(arrays["velocity"], ref_vel, rtol=1e-12, atol=1e-15)
    # the grains are inside the box of the same instant
    b = vtk.vtkXMLPolyDataReader()
    b.SetFileName(str(snaps / f"box_{k:06d}.vtp"))
    b.Update()
    box = b.GetOutput()
    assert box.GetNumberOfPoints() == 8 and box.GetNumberOfPolys() == 6
    x0, x1, y0, y1, z0, z1 = box.GetBounds()
    assert abs(x0) < 1e-12 and abs(x1 - 0.03675) < 1e-9 and abs(y1 - 0.03675) < 1e-9, (x1, y1)
    assert abs((z1 - z0) - 0.1225) < 1e-9, z1 - z0
    assert (ref_pos[:, 2] - 0.003 >= z0 - 1e-4).all(), "grains below the floor"
    print(f"snapshot {k}: 40 grains, 5 arrays, box z ∈ [{z0:.6f}, {z1:.6f}] m — ok")
print("VTK XML snapshots read back with vtk", vtk.vtkVersion.GetVTKVersion())
