# NUMISHEET'93 2D draw bending: blank holder (half), face z = t over the die's face
# (x >= 41.5); written by scripts/make_numisheet93_cases.py
patches 1
patch0_type plane
patch0_origin 41.5,-10,0.78
patch0_e1 0,1,0
patch0_e2 1,0,0
patch0_range 0,30,0,173.5
