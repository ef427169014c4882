// A .geo that never ends: stopped at Mesh/Geo Time Limit.
x = 0;
For i In {1:1e15}
  x = x + 1;
EndFor
