// BasicTest, written for harness jack test from the published description
// of the project 7 test (nand2tetris); the local, argument, this, that and temp segments.

load BasicTest.vm,
output-file BasicTest.out,
compare-to BasicTest.cmp,
output-list RAM[256]%D1.6.1 RAM[300]%D1.6.1 RAM[401]%D1.6.1 RAM[402]%D1.6.1 RAM[3006]%D1.6.1 RAM[3012]%D1.6.1 RAM[3015]%D1.6.1 RAM[11]%D1.6.1;

set sp 256,
set local 300,
set argument 400,
set this 3000,
set that 3010,

repeat 25 {
  vmstep;
}

output;
