"""What a diffusion solve is asked and what it returns, with no method in it: the part
geometries, the exposure history and the Arrhenius diffusivity, the sorption laws, the
plan and the result, and the anisotropic change of variables every method shares."""
