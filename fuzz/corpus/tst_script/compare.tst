load Count.vm, output-file Count.out, compare-to Count.cmp,
output-list RAM[5]%D1.3.1;
repeat 2 { vmstep; }
output;
