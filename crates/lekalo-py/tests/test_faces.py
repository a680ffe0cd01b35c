"""Faces of STEP files: ``lekalo.read_step(path, faces=True)`` gives ``Face`` objects whose
surface and edges are lekalo objects, with the point-in-face test on NumPy arrays."""

from pathlib import Path

import numpy as np
import pytest

import lekalo

HEAD = "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n"
TAIL = "ENDSEC;\nEND-ISO-10303-21;\n"

# a plate 10 x 10 on z = 0 with a hole of radius 2 about (5, 5); face #82 names a missing edge
PLATE = """
#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=PLANE('',#4);
#12=CARTESIAN_POINT('',(10.,0.,0.));
#13=CARTESIAN_POINT('',(10.,10.,0.));
#14=CARTESIAN_POINT('',(0.,10.,0.));
#21=VERTEX_POINT('',#1);
#22=VERTEX_POINT('',#12);
#23=VERTEX_POINT('',#13);
#24=VERTEX_POINT('',#14);
#30=DIRECTION('',(1.,0.,0.));
#31=VECTOR('',#30,1.);
#32=LINE('',#1,#31);
#33=DIRECTION('',(0.,1.,0.));
#34=VECTOR('',#33,1.);
#35=LINE('',#12,#34);
#36=LINE('',#14,#31);
#37=LINE('',#1,#34);
#41=EDGE_CURVE('',#21,#22,#32,.T.);
#42=EDGE_CURVE('',#22,#23,#35,.T.);
#43=EDGE_CURVE('',#24,#23,#36,.T.);
#44=EDGE_CURVE('',#21,#24,#37,.T.);
#51=ORIENTED_EDGE('',*,*,#41,.T.);
#52=ORIENTED_EDGE('',*,*,#42,.T.);
#53=ORIENTED_EDGE('',*,*,#43,.F.);
#54=ORIENTED_EDGE('',*,*,#44,.F.);
#55=EDGE_LOOP('',(#51,#52,#53,#54));
#56=FACE_OUTER_BOUND('',#55,.T.);
#60=CARTESIAN_POINT('',(5.,5.,0.));
#61=AXIS2_PLACEMENT_3D('',#60,#2,#3);
#62=CIRCLE('',#61,2.);
#63=CARTESIAN_POINT('',(7.,5.,0.));
#64=VERTEX_POINT('',#63);
#65=EDGE_CURVE('',#64,#64,#62,.T.);
#66=ORIENTED_EDGE('',*,*,#65,.F.);
#67=EDGE_LOOP('',(#66));
#68=FACE_BOUND('',#67,.T.);
#70=ADVANCED_FACE('plate',(#56,#68),#5,.T.);
#80=EDGE_LOOP('',(#51,#999));
#81=FACE_OUTER_BOUND('',#80,.T.);
#82=ADVANCED_FACE('broken',(#81),#5,.T.);
"""

# a cylinder of radius 1 and height 2: bottom and top circles and the seam, up and down
TUBE = """
#201=CARTESIAN_POINT('',(0.,0.,0.));
#202=DIRECTION('',(0.,0.,1.));
#203=DIRECTION('',(1.,0.,0.));
#204=AXIS2_PLACEMENT_3D('',#201,#202,#203);
#205=CYLINDRICAL_SURFACE('',#204,1.);
#206=CARTESIAN_POINT('',(0.,0.,2.));
#207=AXIS2_PLACEMENT_3D('',#206,#202,#203);
#208=CIRCLE('',#204,1.);
#209=CIRCLE('',#207,1.);
#210=CARTESIAN_POINT('',(1.,0.,0.));
#211=CARTESIAN_POINT('',(1.,0.,2.));
#212=VERTEX_POINT('',#210);
#213=VERTEX_POINT('',#211);
#214=VECTOR('',#202,1.);
#215=LINE('',#210,#214);
#230=EDGE_CURVE('',#212,#212,#208,.T.);
#231=EDGE_CURVE('',#213,#213,#209,.T.);
#232=EDGE_CURVE('',#212,#213,#215,.T.);
#240=ORIENTED_EDGE('',*,*,#230,.T.);
#241=ORIENTED_EDGE('',*,*,#232,.T.);
#242=ORIENTED_EDGE('',*,*,#231,.F.);
#243=ORIENTED_EDGE('',*,*,#232,.F.);
#244=EDGE_LOOP('',(#240,#241,#242,#243));
#245=FACE_OUTER_BOUND('',#244,.T.);
#246=ADVANCED_FACE('tube',(#245),#205,.T.);
"""


# the same cylinder between its circles at z = 0 and z = 2 as two loops, no seam edge: the lower
# circle counter-clockwise from above, the upper clockwise (the face on the left of each)
BAND = TUBE.split("#210=")[0] + """
#210=CARTESIAN_POINT('',(1.,0.,0.));
#211=CARTESIAN_POINT('',(1.,0.,2.));
#212=VERTEX_POINT('',#210);
#213=VERTEX_POINT('',#211);
#230=EDGE_CURVE('',#212,#212,#208,.T.);
#231=EDGE_CURVE('',#213,#213,#209,.T.);
#240=ORIENTED_EDGE('',*,*,#230,.T.);
#241=EDGE_LOOP('',(#240));
#242=FACE_OUTER_BOUND('',#241,.T.);
#243=ORIENTED_EDGE('',*,*,#231,.F.);
#244=EDGE_LOOP('',(#243));
#245=FACE_BOUND('',#244,.T.);
#246=ADVANCED_FACE('band',(#242,#245),#205,.T.);
"""

# the northern half of the unit sphere: one loop, its equator counter-clockwise from above
CAP = """
#301=CARTESIAN_POINT('',(0.,0.,0.));
#302=DIRECTION('',(0.,0.,1.));
#303=DIRECTION('',(1.,0.,0.));
#304=AXIS2_PLACEMENT_3D('',#301,#302,#303);
#305=SPHERICAL_SURFACE('',#304,1.);
#306=CIRCLE('',#304,1.);
#307=CARTESIAN_POINT('',(1.,0.,0.));
#308=VERTEX_POINT('',#307);
#309=EDGE_CURVE('',#308,#308,#306,.T.);
#310=ORIENTED_EDGE('',*,*,#309,.T.);
#311=EDGE_LOOP('',(#310));
#312=FACE_OUTER_BOUND('',#311,.T.);
#313=ADVANCED_FACE('cap',(#312),#305,.T.);
"""


def write(tmp_path, name, data):
    path = tmp_path / name
    path.write_text(HEAD + data + TAIL)
    return path


def test_skipped_entities_are_listed_up_to_a_bound_and_counted_by_kind(tmp_path):
    # 30 faces on a missing surface and 30 unbounded planes: the first `skipped_listed` of each
    # are listed, all counted by kind; None lists every one
    data = "".join(f"#{i}=ADVANCED_FACE('f',(),#999,.T.);\n" for i in range(1, 31))
    data += "#40=CARTESIAN_POINT('',(0.,0.,0.));\n#41=AXIS2_PLACEMENT_3D('',#40,$,$);\n"
    data += "".join(f"#{i}=PLANE('',#41);\n" for i in range(100, 130))
    path = write(tmp_path, "many.step", data)
    r = lekalo.read_step(path, faces=True, skipped_listed=5)
    assert [s["id"] for s in r["skipped"]] == [100, 101, 102, 103, 104]
    assert r["skipped_total"] == 30
    assert r["skipped_kinds"] == [
        {"entity": "PLANE", "reason": r["skipped"][0]["reason"], "count": 30, "first_id": 100}
    ]
    assert [s["id"] for s in r["skipped_faces"]] == [1, 2, 3, 4, 5]
    assert r["skipped_faces_total"] == 30 and r["skipped_faces_kinds"][0]["count"] == 30
    every = lekalo.read_step(path, faces=True, skipped_listed=None)
    assert len(every["skipped"]) == 30 and len(every["skipped_faces"]) == 30
    assert len(lekalo.read_step(path)["skipped"]) == 30  # the default lists 1000
    with pytest.raises(lekalo.InputError, match="skipped_listed"):
        lekalo.read_step(path, skipped_listed=-1)


def test_plate_faces_loops_and_pcurves(tmp_path):
    r = lekalo.read_step(write(tmp_path, "plate.step", PLATE), faces=True)
    assert [f.id for f in r["faces"]] == [70]
    assert r["skipped_faces"][0]["id"] == 82
    assert "#999 of a loop is not defined" in r["skipped_faces"][0]["reason"]
    f = r["faces"][0]
    assert (f.name, f.surface_id, f.same_sense, f.pcurves) == ("plate", 5, True, None)
    assert isinstance(f.surface, lekalo.BSplineSurface)
    assert len(f.outer) == 4 and len(f.inner) == 1 and len(f.inner[0]) == 1
    assert f.edge_ids == [[41, 42, 43, 44], [65]]
    curve, pcurve = f.outer[2]
    # the top edge, used backwards, runs from (10, 10) to (0, 10) in space and in (u, v)
    lo, hi = curve.domain
    np.testing.assert_allclose(curve(np.array([lo, hi])), [[10, 10, 0], [0, 10, 0]], atol=1e-12)
    lo, hi = pcurve.domain
    np.testing.assert_allclose(pcurve(np.array([lo, hi])), [[10, 10], [0, 10]], atol=1e-12)
    assert isinstance(f.inner[0][0][1], lekalo.NurbsCurve) and f.inner[0][0][1].dim == 2


def test_contains_takes_numbers_and_arrays(tmp_path):
    f = lekalo.read_step(write(tmp_path, "plate.step", PLATE), faces=True)["faces"][0]
    assert f.contains(1.0, 1.0) is True
    assert f.contains(5.0, 5.0) is False
    u, v = np.meshgrid(np.linspace(-1, 11, 8), np.linspace(-0.5, 10.5, 6), indexing="ij")
    inside = f.contains(u, v)
    assert inside.shape == (8, 6) and inside.dtype == bool
    expected = (u > 0) & (u < 10) & (v > 0) & (v < 10) & (np.hypot(u - 5, v - 5) > 2)
    np.testing.assert_array_equal(inside, expected)
    polygons = f.trim_polygons()
    assert [p.shape[1] for p in polygons] == [2, 2]
    np.testing.assert_allclose(np.hypot(*(polygons[1] - 5).T), 2, rtol=0.02)


def test_faces_round_trip_through_json(tmp_path):
    f = lekalo.read_step(write(tmp_path, "plate.step", PLATE), faces=True)["faces"][0]
    text = f.to_json()
    g = lekalo.Face.from_json(text)
    assert g.to_json() == text and g.id == 70
    with pytest.raises(lekalo.InputError, match="field `type`"):
        lekalo.Face.from_json(text.replace('"type":"face"', '"type":"surface"'))


def _same_face(a, b):
    """The same surface (by its JSON), sense, and loops: edge curves and pcurves at their
    control points and knots."""
    assert type(a.surface) is type(b.surface)
    assert a.surface.to_json() == b.surface.to_json()
    assert a.same_sense == b.same_sense
    for la, lb in zip([a.outer] + a.inner, [b.outer] + b.inner):
        assert len(la) == len(lb)
        for (ca, pa), (cb, pb) in zip(la, lb):
            assert ca.to_json() == cb.to_json()
            assert pa.to_json() == pb.to_json()


def test_faces_write_to_step_and_iges_and_read_back(tmp_path):
    f = lekalo.read_step(write(tmp_path, "plate.step", PLATE), faces=True)["faces"][0]
    lekalo.write_step(tmp_path / "again.step", [f])
    text = (tmp_path / "again.step").read_text()
    assert "ADVANCED_FACE('plate'" in text and "SURFACE_CURVE" in text and "OPEN_SHELL" in text
    g = lekalo.read_step(tmp_path / "again.step", faces=True)["faces"]
    assert len(g) == 1 and g[0].name == "plate"
    _same_face(f, g[0])
    lekalo.write_iges(tmp_path / "again.igs", [f])
    h = lekalo.read_iges(tmp_path / "again.igs", faces=True)["faces"]
    assert len(h) == 1
    _same_face(f, h[0])
    with pytest.raises(lekalo.InputError, match="no faces"):
        lekalo.write_step(tmp_path / "none.step", [])


def test_cylinder_faces_keep_their_edges_without_pcurves(tmp_path):
    r = lekalo.read_step(write(tmp_path, "tube.step", TUBE), faces=True)
    f = r["faces"][0]
    assert f.edge_ids == [[230, 232, 231, 232]]
    assert all(p is None for _, p in f.outer)
    assert "CYLINDRICAL_SURFACE" in f.pcurves
    with pytest.raises(lekalo.InputError, match="no curve in the surface's"):
        f.contains(0.5, 0.5)


def test_read_step_without_faces_and_with_a_limit(tmp_path):
    path = write(tmp_path, "plate.step", PLATE)
    r = lekalo.read_step(path)
    assert "faces" not in r and r["length_unit"].startswith("millimetre")
    assert any(isinstance(s, lekalo.BSplineSurface) for s in r["shapes"])
    # the keyword to raise, in Python's words: the file is refused while its entity instances
    # are counted, before the count that would admit it is known
    with pytest.raises(lekalo.InputError) as e:
        lekalo.read_step(path, faces=True, max_size=20)
    assert "more than 20 entity instances, above the size limit 20; raise the limit with a larger max_size if" in str(e.value)
    assert "--" not in str(e.value)
    # counts known when refused: the value that admits them (IGES's directory entries, then
    # the control points and knots read so far)
    iges = Path(__file__).parent / "data" / "plate_144.igs"
    with pytest.raises(lekalo.InputError, match=r"16 entities in the directory section, above the size limit 5; raise the limit with max_size=16 if"):
        lekalo.read_iges(iges, max_size=5)
    with pytest.raises(lekalo.InputError, match=r"24 control points and knots with this entity's 6, above the size limit 20; raise the limit with max_size=24 if"):
        lekalo.read_iges(iges, max_size=20)


def test_cad_files_above_the_input_limit_are_refused_by_their_size(tmp_path):
    step = write(tmp_path, "plate.step", PLATE)
    size = step.stat().st_size
    assert lekalo.read_step(step, max_input_bytes=size)["shapes"]
    with pytest.raises(lekalo.InputError) as e:
        lekalo.read_step(step, max_input_bytes=size - 1)
    assert f"{size} bytes, above the input limit of {size - 1} bytes" in str(e.value)
    assert f"raise the limit with max_input_bytes={size} if the input is meant" in str(e.value)
    assert "--" not in str(e.value)
    iges = Path(__file__).parent / "data" / "plate_144.igs"
    with pytest.raises(lekalo.InputError, match="max_input_bytes="):
        lekalo.read_iges(iges, max_input_bytes=100)
    with pytest.raises((lekalo.InputError, ValueError), match="max_input_bytes"):
        lekalo.read_iges(iges, max_input_bytes=-1)


def test_an_endless_device_stops_at_the_input_limit():
    # no size to check first: read through a cap and refused once past it, not read forever
    if not Path("/dev/zero").exists():
        pytest.skip("no /dev/zero")
    with pytest.raises(lekalo.InputError, match=r"more than 4096 bytes.*a larger max_input_bytes"):
        lekalo.read_step("/dev/zero", max_input_bytes=4096)


def test_iges_trimmed_surfaces_read_as_faces():
    # a 10 mm plate (entity 128) trimmed by a 144: outer boundary of four lines (142 over 102
    # composites), a square hole [0.3, 0.7]² (142 over 126 curves); written by the IGES
    # reader's own test, which fails when the file and the writer differ
    path = Path(__file__).parent / "data" / "plate_144.igs"
    plain = lekalo.read_iges(path)
    assert "faces" not in plain and plain["length_unit"] == "MM" and plain["scale_to_mm"] == 1.0
    r = lekalo.read_iges(path, faces=True)
    assert r["skipped_faces"] == []
    [f] = r["faces"]
    assert len(f.outer) == 4 and len(f.inner) == 1
    for curve, pcurve in f.outer + f.inner[0]:
        assert pcurve is not None
        t = np.linspace(*pcurve.domain, 5)
        u, v = np.ascontiguousarray(np.atleast_2d(pcurve(t)).T)
        assert np.allclose(f.surface(u, v), curve(t), atol=1e-12)
    inside = f.contains(np.array([0.1, 0.5, 0.9]), np.array([0.1, 0.5, 0.2]))
    assert list(inside) == [True, False, True]
    assert r["tessellated"] == [], "IGES has no faces of triangles"


# AP242 faces of triangles in inches: a planar face with one normal (not of unit length), a
# strip through pnindex with a normal per point (one zero), a set without normals
TRIANGLES = """
#90=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );
#91=LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#90);
#92=( CONVERSION_BASED_UNIT('INCH',#91) LENGTH_UNIT() NAMED_UNIT(*) );
#93=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#92)) REPRESENTATION_CONTEXT('',''));
#1=COORDINATES_LIST('',4,((0.,0.,0.),(1.,0.,0.),(1.,1.,0.),(0.,1.,0.)));
#2=TRIANGULATED_FACE('square',#1,4,((0.,0.,2.)),$,(),((1,2,3),(1,3,4)));
#3=COORDINATES_LIST('',6,((9.,9.,9.),(1.,0.,0.),(2.,0.,0.),(1.,1.,0.),(2.,1.,0.),(9.,9.,9.)));
#4=COMPLEX_TRIANGULATED_FACE('',#3,4,((0.,0.,1.),(0.,0.6,0.8),(0.,0.,0.),(0.,0.,3.)),$,(2,3,4,5),((1,2,3,4)),());
#5=TRIANGULATED_SURFACE_SET('set',#1,4,(),(),((1,2,3)));
"""


def test_faces_of_triangles_are_read_as_arrays(tmp_path):
    path = write(tmp_path, "tri.stp", TRIANGLES)
    r = lekalo.read_step(path, faces=True)
    assert r["faces"] == [] and r["skipped_faces"] == []
    assert "tessellated" not in lekalo.read_step(path)
    square, strip, surface_set = r["tessellated"]
    assert (square["id"], square["entity"], square["name"], square["link"]) == (2, "TRIANGULATED_FACE", "square", None)
    assert (strip["entity"], surface_set["name"]) == ("COMPLEX_TRIANGULATED_FACE", "set")
    # points in millimetres, (n, 3) float64; pnindex followed (not the list's 6 points)
    v = strip["vertices"]
    assert v.dtype == np.float64 and v.shape == (4, 3)
    assert np.array_equal(v, 25.4 * np.array([[1.0, 0, 0], [2, 0, 0], [1, 1, 0], [2, 1, 0]]))
    # triangles (m, 3) int64, 0-based; the strip's second turned as the first
    t = strip["triangles"]
    assert t.dtype == np.int64 and t.tolist() == [[0, 1, 2], [2, 1, 3]]
    assert square["triangles"].tolist() == [[0, 1, 2], [0, 2, 3]]
    # unit normals per vertex: the planar face's one at each point, a zero one its triangles'
    assert np.allclose(square["normals"], np.tile([0.0, 0.0, 1.0], (4, 1)), rtol=0, atol=1e-15)
    n = strip["normals"]
    assert n.shape == (4, 3)
    assert np.allclose(n, [[0, 0, 1], [0, 0.6, 0.8], [0, 0, 1], [0, 0, 1]], rtol=0, atol=1e-15)
    assert surface_set["normals"] is None
    # every triangle turns about its vertices' normals
    for face in (square, strip):
        p, tri = face["vertices"], face["triangles"]
        turn = np.cross(p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]])
        for k in range(3):
            assert np.all(np.einsum("ij,ij->i", turn, face["normals"][tri[:, k]]) > 0)
    assert strip["dropped"] == 0


def test_mesh_of_the_plate_leaves_the_hole_out(tmp_path):
    f = lekalo.read_step(write(tmp_path, "plate.step", PLATE), faces=True)["faces"][0]
    tol = 1e-3
    vertices, triangles = f.mesh(tol)
    assert vertices.shape[1] == 3 and triangles.shape[1] == 3
    assert triangles.dtype == np.uint32 and triangles.max() < len(vertices)
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    centroids = (a + b + c) / 3.0
    # no triangle in the hole of radius 2 about (5, 5)
    assert np.all(np.hypot(centroids[:, 0] - 5.0, centroids[:, 1] - 5.0) >= 2.0 - tol)
    area = 0.5 * np.abs(np.cross(b - a, c - a)[:, 2]).sum()
    exact = 100.0 - 4.0 * np.pi
    # the polygon of the hole is inside the circle, within tol of it: its area is at most
    # the circle's length times tol smaller
    assert exact - 1e-9 <= area <= exact + 4.0 * np.pi * tol
    with pytest.raises(ValueError, match="tolerance"):
        f.mesh(0.0)


def test_mesh_of_a_tube_without_pcurves_projects_its_edges(tmp_path):
    # the tube's edges are given as 3-D curves only: two circles and the seam line used twice
    f = lekalo.read_step(write(tmp_path, "tube.step", TUBE), faces=True)["faces"][0]
    assert all(p is None for _, p in f.outer)
    g = f.with_projected_pcurves(1e-7)
    assert g.pcurves is None and g.edge_ids == f.edge_ids
    (u0, u1), (v0, v1) = g.surface.domain
    for curve, pcurve in g.outer:
        assert pcurve.domain == curve.domain
        t = np.linspace(*curve.domain, 33)
        u, v = np.ascontiguousarray(np.atleast_2d(pcurve(t)).T)
        # the loop lies in the domain, up to rounding at the seam
        assert u.min() >= u0 - 1e-9 and u.max() <= u1 + 1e-9
        uv = np.clip(u, u0, u1), np.clip(v, v0, v1)
        assert np.allclose(g.surface(*uv), curve(t), atol=1e-7)
    tol = 1e-3
    vertices, triangles = f.mesh(tol)
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    # radius 1, height 2: inscribed triangles within tol lose at most tol of the area per unit
    # area, and the trims at most tol times their length (two circles and the seam twice)
    exact, perimeter = 4.0 * np.pi, 4.0 * np.pi + 4.0
    assert abs(area - exact) <= (exact + perimeter) * tol
    # every triangle's normal points out of the tube, as the face's does
    n = np.cross(b - a, c - a)
    centroids = (a + b + c) / 3.0
    assert np.all(np.einsum("ij,ij->i", n[:, :2], centroids[:, :2]) > 0)
    with pytest.raises(ValueError, match="tolerance"):
        f.with_projected_pcurves(0.0)


def open_edges(vertices, triangles):
    """The edges used by one triangle only, their ends taken by their coordinates."""
    key = [tuple(p) for p in vertices]
    count = {}
    for t in triangles:
        for i, j in ((0, 1), (1, 2), (2, 0)):
            e = tuple(sorted((key[t[i]], key[t[j]])))
            count[e] = count.get(e, 0) + 1
    return [e for e, n in count.items() if n == 1]


@pytest.mark.parametrize(
    "name, data, exact, perimeter, on_loop",
    [
        # 2 pi r h, the two circles
        ("band", BAND, 4.0 * np.pi, 4.0 * np.pi, lambda p: min(abs(p[2]), abs(p[2] - 2.0))),
        # 2 pi r^2 (1 - cos theta) at theta = pi/2, the equator
        ("cap", CAP, 2.0 * np.pi, 2.0 * np.pi, lambda p: abs(p[2])),
    ],
)
def test_mesh_of_a_band_and_a_cap_without_a_seam_edge(tmp_path, name, data, exact, perimeter, on_loop):
    f = lekalo.read_step(write(tmp_path, f"{name}.step", data), faces=True)["faces"][0]
    tol = 1e-3
    vertices, triangles = f.mesh(tol)
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    n = np.cross(b - a, c - a)
    area = 0.5 * np.linalg.norm(n, axis=1).sum()
    # radius 1: within tol of the area per unit area and tol times the loops' length
    assert abs(area - exact) <= (exact + perimeter) * tol
    # no crack along the cut: every open edge is on the face's loops
    edges = open_edges(vertices, triangles)
    assert edges
    assert all(on_loop(p) < 1e-9 for e in edges for p in e)
    # normals out of the cylinder, out of the sphere
    centroids = (a + b + c) / 3.0
    out = centroids if name == "cap" else centroids * [1.0, 1.0, 0.0]
    assert np.all(np.einsum("ij,ij->i", n, out) > 0)


def test_mesh_faces_lists_the_faces_that_fail_and_meshes_the_others_as_without_them(tmp_path):
    import json

    plate = lekalo.read_step(write(tmp_path, "plate.step", PLATE), faces=True)["faces"][0]
    tube = lekalo.read_step(write(tmp_path, "tube.step", TUBE), faces=True)["faces"][0]
    # the plate without pcurves, its plane lifted 1 mm off its edges: its projection fails
    d = json.loads(plate.to_json())
    for lp in [d["outer"], *d.get("inner", [])]:
        for e in lp:
            e.pop("pcurve", None)
    for c in d["surface"]["control"]:
        c[2] += 1.0
    lifted = lekalo.Face.from_json(json.dumps(d))
    tol = 1e-3
    vertices, triangles, normals, failures = lekalo.mesh_faces([tube, lifted, plate], tol)
    assert [k for k, _ in failures] == [1]
    assert "does not lie on the face's surface" in failures[0][1]
    assert triangles.dtype == np.uint32 and triangles.max() < len(vertices)
    alone_v, alone_t, alone_n, none = lekalo.mesh_faces([tube, plate], tol)
    assert none == []
    assert np.array_equal(vertices, alone_v) and np.array_equal(triangles, alone_t)
    assert np.array_equal(normals, alone_n)
    # the tube and the plate share no edge: the joined mesh is the two meshes one after the other
    tv, tt = tube.mesh(tol)
    pv, pt = plate.mesh(tol)
    assert np.array_equal(vertices, np.vstack([tv, pv]))
    assert np.array_equal(triangles, np.vstack([tt, pt + len(tv)]))
    with pytest.raises(ValueError, match="tolerance"):
        lekalo.mesh_faces([plate], 0.0)


# the same half sphere as a face whose normal points into the sphere: its loop runs the equator
# clockwise from above, the face on its left seen from inside
CAP_INWARD = CAP.replace("#310=ORIENTED_EDGE('',*,*,#309,.T.);", "#310=ORIENTED_EDGE('',*,*,#309,.F.);").replace(
    "#313=ADVANCED_FACE('cap',(#312),#305,.T.);", "#313=ADVANCED_FACE('cap',(#312),#305,.F.);"
)


def turn_with_their_normals(vertices, triangles, normals):
    """Every triangle turns counter-clockwise about the normals of its three vertices."""
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    turn = np.cross(b - a, c - a)
    return all(np.all(np.einsum("ij,ij->i", turn, normals[triangles[:, k]]) > 0) for k in range(3))


@pytest.mark.parametrize("data, sign", [(CAP, 1.0), (CAP_INWARD, -1.0)])
def test_mesh_faces_gives_the_surfaces_exact_unit_normals_turned_by_the_face(tmp_path, data, sign):
    cap = lekalo.read_step(write(tmp_path, "cap.step", data), faces=True)["faces"][0]
    vertices, triangles, normals, failures = lekalo.mesh_faces([cap], 1e-3)
    assert failures == []
    assert normals.dtype == np.float64 and normals.shape == vertices.shape
    # every vertex has its unit normal, the copies of the pole that no triangle uses too
    used = np.zeros(len(vertices), dtype=bool)
    used[triangles.ravel()] = True
    assert used.sum() > 0.99 * len(vertices)
    assert np.allclose(np.linalg.norm(normals, axis=1), 1.0, rtol=0, atol=1e-12)
    # the unit sphere about the origin: its outward normal at p is p itself; the face's is the
    # surface's turned by its sense
    pole = np.abs(vertices[:, 2] - 1.0) < 1e-12
    assert np.abs(normals[~pole] - sign * vertices[~pole]).max() < 1e-9
    # at the pole S_u x S_v vanishes: the limit normal along the collapsed edge, the axis
    assert pole.any()
    assert np.abs(normals[pole] - sign * np.array([0.0, 0.0, 1.0])).max() < 1e-12
    assert turn_with_their_normals(vertices, triangles, normals)


def test_mesh_faces_joins_the_faces_of_triangles_with_their_normals(tmp_path):
    cap = lekalo.read_step(write(tmp_path, "cap.step", CAP), faces=True)["faces"][0]
    tess = lekalo.read_step(write(tmp_path, "tri.stp", TRIANGLES), faces=True)["tessellated"]
    cv, ct, cn, _ = lekalo.mesh_faces([cap], 1e-3)
    vertices, triangles, normals, failures = lekalo.mesh_faces([cap], 1e-3, tessellated=tess)
    assert failures == []
    # the meshed face first, as alone; then each face of triangles as the file gives it
    k = len(cv)
    assert np.array_equal(vertices[:k], cv) and np.array_equal(normals[:k], cn)
    assert np.array_equal(triangles[: len(ct)], ct)
    assert np.array_equal(vertices[k:], np.vstack([t["vertices"] for t in tess]))
    offsets = k + np.cumsum([0] + [len(t["vertices"]) for t in tess[:-1]])
    given = np.vstack([t["triangles"] + o for t, o in zip(tess, offsets)])
    assert np.array_equal(triangles[len(ct):], given)
    # their normals the file's made unit; the set without normals has none: zeros
    square, strip, surface_set = tess
    assert np.array_equal(normals[k : k + 4], square["normals"])
    assert np.array_equal(normals[k + 4 : k + 8], strip["normals"])
    assert np.array_equal(normals[k + 8 :], np.zeros((4, 3)))
    assert turn_with_their_normals(vertices[: k + 8], triangles[: len(ct) + 4], normals[: k + 8])
    # faces of triangles only, none of which gives normals: no normals at all
    v, t, n, f = lekalo.mesh_faces([], 1e-3, tessellated=[surface_set])
    assert n is None and f == [] and t.tolist() == [[0, 1, 2]] and len(v) == 4
    # lists of numbers do as arrays do
    plain = {"vertices": square["vertices"].tolist(), "triangles": square["triangles"].tolist(), "normals": None}
    v, t, n, f = lekalo.mesh_faces([], 1e-3, tessellated=[plain])
    assert np.array_equal(v, square["vertices"]) and t.tolist() == [[0, 1, 2], [0, 2, 3]] and n is None
    # a face of triangles that does not hold together is named by its place and id
    bad = dict(square, triangles=np.array([[0, 1, 9]]))
    with pytest.raises(ValueError, match=r"face of triangles: 1 \(#2\): triangle 0 has index 9, past its 4 points"):
        lekalo.mesh_faces([cap], 1e-3, tessellated=[strip, bad])
    with pytest.raises(ValueError, match=r"tessellated\[0\]\[\'triangles\'\]: triangle 0 has index -1"):
        lekalo.mesh_faces([], 1e-3, tessellated=[dict(square, triangles=np.array([[-1, 1, 2]]))])
    with pytest.raises(ValueError, match=r"tessellated\[0\]: no 'vertices'"):
        lekalo.mesh_faces([], 1e-3, tessellated=[{"triangles": [[0, 1, 2]]}])


def _plate_with(plate, inner, face_id):
    import json

    d = json.loads(plate.to_json())
    d["id"] = face_id
    d["inner"] = inner
    return lekalo.Face.from_json(json.dumps(d))


def _moved(loop, du):
    import copy

    loop = copy.deepcopy(loop)
    for e in loop:
        for key in ("curve", "pcurve"):
            for c in e[key]["control"]:
                c[0] += du
    return loop


def test_faces_with_bad_trims_are_refused_naming_the_loop_and_repairs_are_warned(tmp_path):
    import json

    plate = lekalo.read_step(write(tmp_path, "plate.step", PLATE), faces=True)["faces"][0]
    assert plate.check_trims() == []
    hole = json.loads(plate.to_json())["inner"][0]
    # the hole moved 4 along u leaves the plane's domain [0, 10]
    outside = _plate_with(plate, [_moved(hole, 4.0)], 77)
    with pytest.raises(ValueError, match=r"inner loop 1 leaves the surface's domain: .* past its side u = 10;"):
        outside.check_trims()
    with pytest.raises(ValueError, match="inner loop 1 leaves"):
        outside.mesh(1e-2)
    # two holes crossing
    crossing = _plate_with(plate, [hole, _moved(hole, 1.0)], 79)
    with pytest.raises(ValueError, match="inner loop 2 crosses inner loop 1"):
        crossing.check_trims()
    # a hole of one point: dropped, the repair named
    def line(c):
        return {"lekalo": 1, "type": "bspline_curve", "degree": 1,
                "knots": [0, 0, 1, 1], "control": [c, c]}

    point = _plate_with(plate, [[{"curve": line([5.0, 5.0, 0.0]),
                                  "pcurve": line([5.0, 5.0])}]], 78)
    assert point.check_trims() == ["inner loop 1 has no length (a hole of one point): dropped"]
    with pytest.warns(UserWarning, match="face 1: inner loop 1 has no length"):
        vertices, triangles, _, failures = lekalo.mesh_faces([outside, point, crossing], 1e-2)
    assert [k for k, _ in failures] == [0, 2]
    assert "leaves the surface's domain" in failures[0][1]
    assert "crosses inner loop 1" in failures[1][1]
    # the plate without its hole: area 100
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    assert abs(0.5 * np.abs(np.cross(b - a, c - a)[:, 2]).sum() - 100.0) < 1e-9


def test_a_missing_cad_file_is_named_with_the_fix(tmp_path):
    # the operating system's "No such file or directory (os error 2)" named no fix
    for read in (lekalo.read_step, lekalo.read_iges):
        with pytest.raises(lekalo.InputError, match="no such file; check the name") as e:
            read(str(tmp_path / "nope.step"))
        assert "os error" not in str(e.value)


def test_a_file_that_cannot_be_read_is_also_the_oserror_python_raises(tmp_path):
    # a SciPy/NumPy user writes `except FileNotFoundError`, as for open() and np.load;
    # `except lekalo.InputError` and `except ValueError` still catch it
    import errno
    import os

    locked = write(tmp_path, "locked.step", PLATE)
    os.chmod(locked, 0)
    cases = [
        (tmp_path / "nope.step", FileNotFoundError, lekalo.MissingFileError, errno.ENOENT),
        (tmp_path, IsADirectoryError, lekalo.NotAFileError, errno.EISDIR),
    ]
    if not os.access(locked, os.R_OK):  # root reads any file
        cases.append((locked, PermissionError, lekalo.FileAccessError, errno.EACCES))
    for read in (lekalo.read_step, lekalo.read_iges):
        for path, builtin, cls, code in cases:
            with pytest.raises(builtin) as e:
                read(str(path))
            assert type(e.value) is cls
            assert isinstance(e.value, lekalo.InputError) and isinstance(e.value, ValueError)
            assert e.value.errno == code and e.value.filename == str(path)
            assert str(e.value).startswith(f"cannot read {path}: "), str(e.value)
            assert "os error" not in str(e.value) and "Errno" not in str(e.value)
    os.chmod(locked, 0o644)
