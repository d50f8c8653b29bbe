"""The 3D medial axis transform of extrusions and revolutions, lifted from the 2D MAT."""
