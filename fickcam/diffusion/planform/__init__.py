"""The in-plane shape of a prismatic part (CamPlate, LinkBar): its outline and plane
geometry, the exact short-time expansion of its uptake, its triangle meshes and its
Delaunay-admissible cells, and the moments of cell values over the part and its layer."""
