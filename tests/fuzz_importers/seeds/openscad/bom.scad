sphere(r=1);
