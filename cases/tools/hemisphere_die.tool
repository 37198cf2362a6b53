# die fillet of the stretching benchmark: one torus patch (doc/tools.md)
patches 1
patch0_type torus
patch0_center 0,0,7.35
patch0_axis 0,0,1
patch0_ref 1,0,0
patch0_major 59.18
patch0_minor 6.35
patch0_range -10,100,180,270
