// StaticTest, written for harness jack test from the published description
// of the project 7 test (nand2tetris); the static segment.

load StaticTest.vm,
output-file StaticTest.out,
compare-to StaticTest.cmp,
output-list RAM[256]%D1.6.1;

set sp 256,

repeat 11 {
  vmstep;
}

output;
