// Hertz test (tests/apps/hertz_test.cpp): the lower half of an elastic sphere, R = 0.05 m.
// Its pole (the contact point) is at the origin, its axis along y, its flat top at y = R.
// The cap_*.geo files differ only in hc, the element size at the contact (see hertz_test.cpp).
SetFactory("OpenCASCADE");
R = 0.05;        // sphere radius (m)
hc = 1.0e-3;     // element size within r0 of the pole (m)
r0 = 6e-3;       // radius of the uniformly refined zone (m): the largest contact radius is 5.1 mm
r1 = 30e-3;      // the size grows linearly to hf at this distance (m)
hf = 10e-3;      // element size far from the pole (m): the scene's mesh_size must not be smaller

Sphere(1) = {0, R, 0, R};
Rotate {{1, 0, 0}, {0, R, 0}, Pi / 2} { Volume{1}; }   // OCC's poles are on z: put them on y
Box(2) = {-R, -R, -R, 2 * R, 2 * R, 2 * R};   // the lower half, y in [0, R]
cap() = BooleanIntersection{ Volume{1}; Delete; }{ Volume{2}; Delete; };

// Nodes on the axis at depths 5, 10 and 20 mm: the reference points of the local indentation.
Point(101) = {0, 0.005, 0};
Point(102) = {0, 0.010, 0};
Point(103) = {0, 0.020, 0};
Point{101, 102, 103} In Volume{cap(0)};

pole() = Point In BoundingBox{-1e-9, -1e-9, -1e-9, 1e-9, 1e-9, 1e-9};
Field[1] = Distance;
Field[1].PointsList = {pole()};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = hf;
Field[2].DistMin = r0;
Field[2].DistMax = r1;
Background Field = 2;
