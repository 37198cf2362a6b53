# a plane and a sphere patch
patches 2
patch0_type plane
patch0_origin 0,0,0
patch0_e1 1,0,0
patch0_e2 0,1,0
patch0_range 0,1,0,1
patch1_type sphere
patch1_center 0,0,-1
patch1_radius 1
patch1_axis 0,0,1
patch1_ref 1,0,0
patch1_range 0,90,0,90
