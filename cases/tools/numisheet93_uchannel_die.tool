# NUMISHEET'93 2D draw bending: die (half), face z = 0, opening 73 (half 36.5),
# shoulder radius 5; written by scripts/make_numisheet93_cases.py
patches 3
patch0_type plane
patch0_origin 41.5,-10,0
patch0_e1 1,0,0
patch0_e2 0,1,0
patch0_range 0,173.5,0,30
patch1_type cylinder
patch1_center 41.5,0,-5
patch1_axis 0,1,0
patch1_ref 0,0,1
patch1_radius 5
patch1_range -90,0,-10,20
patch2_type plane
patch2_origin 36.5,-10,-100
patch2_e1 0,0,1
patch2_e2 0,1,0
patch2_range 0,95,0,30
