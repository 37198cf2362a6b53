# NUMISHEET'93 square cup: blank holder (quarter), face z = t over the die's face;
# written by scripts/make_numisheet93_cases.py
patches 3
patch0_type plane
patch0_origin 45,-5,0.81
patch0_e1 1,0,0
patch0_e2 0,1,0
patch0_range 0,85,0,30
patch0_sense -1
patch1_type plane
patch1_origin -5,45,0.81
patch1_e1 1,0,0
patch1_e2 0,1,0
patch1_range 0,30,0,85
patch1_sense -1
patch2_type coons
patch2_bottom_type arc
patch2_bottom_points 45,25,0.81,25,45,0.81,25,25,0.81
patch2_top_type arc
patch2_top_points 130,25,0.81,25,130,0.81,25,25,0.81
patch2_left_type line
patch2_left_points 45,25,0.81,130,25,0.81
patch2_right_type line
patch2_right_points 25,45,0.81,25,130,0.81
