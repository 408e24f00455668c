// A 0.2 × 0.1 × 0.1 m box (OpenCASCADE numbering: surface 1 is the face x = 0),
// with a named face and a named volume. Meshed by stiffsoft with its own h.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.1, 0.1};
Physical Surface("left") = {1};
Physical Volume("body") = {1};
