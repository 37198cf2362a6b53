# NUMISHEET'93 square cup: punch (quarter, x, y >= 0), 70 x 70, plan corner radius 10,
# profile radius 8, head on the sheet's top face z = t at load 0 (one square plane); the corner
# blend is a spindle torus (major radius 2 < minor 8) on its outer part;
# written by scripts/make_numisheet93_cases.py
patches 7
patch0_type plane
patch0_origin -5,-5,0.81
patch0_e1 0,1,0
patch0_e2 1,0,0
patch0_range 0,32,0,32
patch1_type cylinder
patch1_center 27,0,8.81
patch1_axis 0,-1,0
patch1_ref 0,0,-1
patch1_radius 8
patch1_range 0,90,-25,5
patch2_type cylinder
patch2_center 0,27,8.81
patch2_axis 1,0,0
patch2_ref 0,0,-1
patch2_radius 8
patch2_range 0,90,-5,25
patch3_type torus
patch3_center 25,25,8.81
patch3_axis 0,0,1
patch3_ref 1,0,0
patch3_major 2
patch3_minor 8
patch3_range 0,90,-90,0
patch4_type plane
patch4_origin 35,-5,8.81
patch4_e1 0,1,0
patch4_e2 0,0,1
patch4_range 0,30,0,80
patch5_type plane
patch5_origin -5,35,8.81
patch5_e1 0,0,1
patch5_e2 1,0,0
patch5_range 0,80,0,30
patch6_type cylinder
patch6_center 25,25,8.81
patch6_axis 0,0,1
patch6_ref 1,0,0
patch6_radius 10
patch6_range 0,90,0,80
