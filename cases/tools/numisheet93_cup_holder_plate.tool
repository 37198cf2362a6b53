# NUMISHEET'93 square cup, elastic blank holder: the press's plane on the plate's top z = 25.78
# (quarter, beyond the plate's 75 x 75 by 10 mm), normal -z; written by
# scripts/make_cup_elastic_holder.py
patches 1
patch0_type plane
patch0_origin -10,-10,25.78
patch0_e1 1,0,0
patch0_e2 0,1,0
patch0_range 0,95,0,95
patch0_sense -1
