# NUMISHEET'93 2D draw bending: punch (half), head on the sheet's top face z = t at load 0,
# width 70 (half 35), corner radius 5; written by scripts/make_numisheet93_cases.py
patches 3
patch0_type plane
patch0_origin -5,-10,0.78
patch0_e1 0,1,0
patch0_e2 1,0,0
patch0_range 0,30,0,35
patch1_type cylinder
patch1_center 30,0,5.78
patch1_axis 0,-1,0
patch1_ref 0,0,-1
patch1_radius 5
patch1_range 0,90,-20,10
patch2_type plane
patch2_origin 35,-10,5.78
patch2_e1 0,1,0
patch2_e2 0,0,1
patch2_range 0,30,0,100
