MODULE demo
  ! Joint targets as in the manual: robot axes in degrees, 9E9 where there is no external axis
  CONST jointtarget calib_pos := [[0, 0, 0, 0, 0, 0], [0, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget p50 := [[10, 20.5, -30, 0, 45, 90], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  PERS tooldata grip2 := [TRUE, [[97.4, 0, 223.1], [0.924, 0, 0.383, 0]], [5, [23, 0, 75], [1, 0, 0, 0], 0, 0, 0]];
  CONST jointtarget path{2} := [[[1, 2, 3, 4, 5, 6], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]],
    [[2, 3, 4, 5, 6, 7], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]]];
  PROC main()
    MoveAbsJ calib_pos, v100, fine, tool0;
    MoveAbsJ p50, v1000, z50, grip2;
    MoveAbsJ \Conc, p50\NoEOffs, v1000\T:=5, fine, grip2;
    MoveAbsJ [[5, 5, 5, 0, 5, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v500\T:=2.5, z10, tool0 \WObj:=wobj0;
    MoveAbsJ path{2}\NoEOffs, v1000\T:=0.5, fine, tool0;
  ENDPROC
ENDMODULE
