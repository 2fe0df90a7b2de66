// PointerTest, written for harness jack test from the published description
// of the project 7 test (nand2tetris); pointer 0 and 1 with this and that.

load PointerTest.vm,
output-file PointerTest.out,
compare-to PointerTest.cmp,
output-list RAM[256]%D1.6.1 RAM[3]%D1.6.1 RAM[4]%D1.6.1 RAM[3032]%D1.6.1 RAM[3046]%D1.6.1;

set sp 256,

repeat 15 {
  vmstep;
}

output;
