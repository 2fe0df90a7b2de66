// SimpleAdd, written for harness jack test from the published description
// of the project 7 test (nand2tetris); 7 + 8.

load SimpleAdd.vm,
output-file SimpleAdd.out,
compare-to SimpleAdd.cmp,
output-list RAM[0]%D2.6.2 RAM[256]%D2.6.2;

set sp 256,

repeat 3 {
  vmstep;
}

output;
