/PROG  PICK
/ATTR
OWNER		= MNEDITOR;
COMMENT		= "Pick part";
PROG_SIZE	= 636;
CREATE		= DATE 19-07-18  TIME 10:21:44;
MODIFIED	= DATE 19-07-18  TIME 10:24:02;
FILE_NAME	= ;
VERSION		= 0;
LINE_COUNT	= 5;
MEMORY_SIZE	= 1036;
PROTECT		= READ_WRITE;
TCD:  STACK_SIZE	= 0,
      TASK_PRIORITY	= 50,
      TIME_SLICE	= 0,
      BUSY_LAMP_OFF	= 0,
      ABORT_REQUEST	= 0,
      PAUSE_REQUEST	= 0;
DEFAULT_GROUP	= 1,*,*,*,*;
CONTROL_CODE	= 00000000 00000000;
/APPL
/MN
   1:  !Move to the part ;
   2:J P[1] 100% FINE    ;
   3:J P[2] 500msec CNT100    ;
   4:L P[3] 100mm/sec FINE    ;
   5:  WAIT   1.00(sec) ;
/POS
P[1]{
   GP1:
	UF : 0, UT : 1,	
	J1=     0.000 deg,	J2=    -1.908 deg,	J3=   -14.270 deg,
	J4=    -0.000 deg,	J5=   -27.007 deg,	J6=     0.000 deg
};
P[2]{
   GP1:
	UF : 0, UT : 1,	
	J1=    10.000 deg,	J2=     5.500 deg,	J3=   -10.250 deg,
	J4=     0.000 deg,	J5=   -70.000 deg,	J6=    15.000 deg
};
P[3]{
   GP1:
	UF : 0, UT : 1,	
	J1=    20.000 deg,	J2=    10.000 deg,	J3=    -5.000 deg,
	J4=     0.000 deg,	J5=   -85.000 deg,	J6=    30.000 deg
};
/END
