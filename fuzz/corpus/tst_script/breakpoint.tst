load Count.vm, output-file L.out, output-list line%S1.16.1 currentFunction%S1.12.1 sp%D1.6.1;
breakpoint RAM[5] 1;
repeat 10 { vmstep; output; }
clear-breakpoints, echo "done";
vmstep! output;
