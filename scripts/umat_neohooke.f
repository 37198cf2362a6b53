C     Compressible neo-Hookean solid as an Abaqus/Standard UMAT, for the ironing case's check of
C     the material law (doc/notes/ironing.md; scripts/make_ironing_case.py):
C
C       W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2
C       sigma = (mu (b - 1) + lambda ln J 1) / J           (b = F F^T, J = det F)
C
C     the law of the Kratos HyperElastic3DLaw that the ironing reference was run with; its
C     small-strain moduli are those of E and nu (PROPS(1), PROPS(2)). Stateless: the stress is a
C     function of DFGRD1 alone. DDSDDE is Abaqus's Jacobian of the Jaumann rate of the Kirchhoff
C     stress over J, C = c + (delta_ik sigma_jl + delta_il sigma_jk + delta_jk sigma_il
C     + delta_jl sigma_ik)/2 with the spatial elasticity c = (lambda 1 x 1 + 2 (mu - lambda ln J) I)/J.
C     The code's bridge (doc/umat.md) reads it as exact for an update that depends on the
C     deformation through DSTRAN only; this one reads DFGRD1, so the assembled tangent is exact
C     to first order in the increment (Newton still converges, linearly in its last digits).
C
C     gfortran -O2 -shared -fPIC scripts/umat_neohooke.f -o /tmp/umat_neohooke.so
C     -material_type umat -material_umat /tmp/umat_neohooke.so -material_umat_props E,nu
      SUBROUTINE UMAT(STRESS,STATEV,DDSDDE,SSE,SPD,SCD,
     1 RPL,DDSDDT,DRPLDE,DRPLDT,
     2 STRAN,DSTRAN,TIME,DTIME,TEMP,DTEMP,PREDEF,DPRED,CMNAME,
     3 NDI,NSHR,NTENS,NSTATV,PROPS,NPROPS,COORDS,DROT,PNEWDT,
     4 CELENT,DFGRD0,DFGRD1,NOEL,NPT,LAYER,KSPT,KSTEP,KINC)
      IMPLICIT NONE
      CHARACTER*80 CMNAME
      INTEGER NDI,NSHR,NTENS,NSTATV,NPROPS,NOEL,NPT,LAYER,KSPT,
     1 KSTEP,KINC
      DOUBLE PRECISION STRESS(NTENS),STATEV(*),DDSDDE(NTENS,NTENS),
     1 SSE,SPD,SCD,RPL,DDSDDT(NTENS),DRPLDE(NTENS),DRPLDT,
     2 STRAN(NTENS),DSTRAN(NTENS),TIME(2),DTIME,TEMP,DTEMP,
     3 PREDEF(*),DPRED(*),PROPS(NPROPS),COORDS(3),DROT(3,3),
     4 PNEWDT,CELENT,DFGRD0(3,3),DFGRD1(3,3)
      DOUBLE PRECISION E,XNU,XMU,XLAM,DETF,XLNJ,B(3,3),S(3,3),
     1 C4,DEL(3,3)
      INTEGER I,J,K,L,M,N,II(6),JJ(6)
      DATA II /1,2,3,1,1,2/
      DATA JJ /1,2,3,2,3,3/
      E = PROPS(1)
      XNU = PROPS(2)
      XMU = E/(2.D0*(1.D0+XNU))
      XLAM = E*XNU/((1.D0+XNU)*(1.D0-2.D0*XNU))
      DETF = DFGRD1(1,1)*(DFGRD1(2,2)*DFGRD1(3,3)
     1     - DFGRD1(2,3)*DFGRD1(3,2))
     2     - DFGRD1(1,2)*(DFGRD1(2,1)*DFGRD1(3,3)
     3     - DFGRD1(2,3)*DFGRD1(3,1))
     4     + DFGRD1(1,3)*(DFGRD1(2,1)*DFGRD1(3,2)
     5     - DFGRD1(2,2)*DFGRD1(3,1))
      IF (DETF .LE. 0.D0) THEN
        PNEWDT = 0.5D0
        RETURN
      END IF
      XLNJ = LOG(DETF)
      DO I = 1, 3
        DO J = 1, 3
          DEL(I,J) = 0.D0
          B(I,J) = 0.D0
          DO K = 1, 3
            B(I,J) = B(I,J) + DFGRD1(I,K)*DFGRD1(J,K)
          END DO
        END DO
        DEL(I,I) = 1.D0
      END DO
      DO I = 1, 3
        DO J = 1, 3
          S(I,J) = (XMU*(B(I,J)-DEL(I,J)) + XLAM*XLNJ*DEL(I,J))/DETF
        END DO
      END DO
      DO M = 1, NTENS
        STRESS(M) = S(II(M),JJ(M))
      END DO
      DO M = 1, NTENS
        I = II(M)
        J = JJ(M)
        DO N = 1, NTENS
          K = II(N)
          L = JJ(N)
          C4 = (XLAM*DEL(I,J)*DEL(K,L) + (XMU-XLAM*XLNJ)*
     1         (DEL(I,K)*DEL(J,L)+DEL(I,L)*DEL(J,K)))/DETF
          C4 = C4 + 0.5D0*(DEL(I,K)*S(J,L)+DEL(I,L)*S(J,K)
     1         + DEL(J,K)*S(I,L)+DEL(J,L)*S(I,K))
          DDSDDE(M,N) = C4
        END DO
      END DO
      RETURN
      END
