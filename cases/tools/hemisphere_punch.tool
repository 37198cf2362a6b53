# hemispherical punch of the stretching benchmark: one sphere patch (doc/tools.md)
patches 1
patch0_type sphere
patch0_center 0,0,-50.8
patch0_radius 50.8
patch0_axis 0,0,1
patch0_ref 1,0,0
patch0_range 0,90,-10,100
