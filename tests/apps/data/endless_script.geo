// Hard case (tests/apps/load_timeout_test.cpp): a gmsh script that never ends. Loading it
// must be stopped by `stiffsoft run --load-timeout`.
For i In {1:1e15}
EndFor
Box(1) = {0, 0, 0, 0.1, 0.1, 0.1};
