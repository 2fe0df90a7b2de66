// StaticsTest, written for harness jack test from the published description
// of the project 8 test (nand2tetris); statics kept apart per file.

load,
output-file StaticsTest.out,
compare-to StaticsTest.cmp,
output-list RAM[0]%D1.6.1 RAM[261]%D1.6.1 RAM[262]%D1.6.1;

set sp 261,

repeat 36 {
  vmstep;
}

output;
