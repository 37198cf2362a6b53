# hemispherical punch benchmark, the die: the paper's own Coons patches (punch 3 + 1 plane, die fillet 1).
# Written by scripts/make_hemisphere_cases.py (scripts/coons_tools.py).
patches 1
patch0_type coons
patch0_sense -1
patch0_bottom_type arc
patch0_bottom_points 59.18,0,1,3.62372987867702e-15,59.18,1,0,0,1
patch0_top_type arc
patch0_top_points 52.83,0,7.35,3.23490451994773e-15,52.83,7.35,0,0,7.35
patch0_left_type arc
patch0_left_points 59.18,0,1,52.83,0,7.35,59.18,0,7.35
patch0_right_type arc
patch0_right_points 3.62372987867702e-15,59.18,1,3.23490451994773e-15,52.83,7.35,3.62372987867702e-15,59.18,7.35
