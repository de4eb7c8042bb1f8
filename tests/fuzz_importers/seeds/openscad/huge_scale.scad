scale([1e308, 1, 1]) sphere(1);
