// StackTest, written for harness jack test from the published description
// of the project 7 test (nand2tetris); eq, lt, gt, arithmetic and logic.

load StackTest.vm,
output-file StackTest.out,
compare-to StackTest.cmp,
output-list RAM[0]%D1.6.1 RAM[256]%D1.6.1 RAM[257]%D1.6.1 RAM[258]%D1.6.1 RAM[259]%D1.6.1 RAM[260]%D1.6.1 RAM[261]%D1.6.1 RAM[262]%D1.6.1 RAM[263]%D1.6.1 RAM[264]%D1.6.1 RAM[265]%D1.6.1;

set sp 256,

repeat 38 {
  vmstep;
}

output;
