sphere(r=-1);
