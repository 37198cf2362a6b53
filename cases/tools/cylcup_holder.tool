# cylindrical cup (doc/tutorial.md): blank holder, face z = t over the die's face; written by scripts/make_cylcup_tools.py
patches 1
patch0_type coons
patch0_bottom_type arc
patch0_bottom_points 31.5138480964,-5.55674168534,1,-5.55674168534,31.5138480964,1,0,0,1
patch0_top_type arc
patch0_top_points 64.0125039458,-11.2871315484,1,-11.2871315484,64.0125039458,1,0,0,1
patch0_left_type line
patch0_left_points 31.5138480964,-5.55674168534,1,64.0125039458,-11.2871315484,1
patch0_right_type line
patch0_right_points -5.55674168534,31.5138480964,1,-11.2871315484,64.0125039458,1
patch0_sense 1
