/* a comment */ load Count.vm,
set sp 300, set RAM[301] -2, set temp[1] 9, set local 400, set argument[0] 5;
output-file S.out, output-list RAM[301]%X1.4.1 temp[1]%B1.16.1 argument[0]%D2.6.2;
repeat 3 { vmstep; } output; // end
