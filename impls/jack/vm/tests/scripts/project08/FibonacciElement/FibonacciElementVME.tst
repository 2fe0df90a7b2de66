// FibonacciElement, written for harness jack test from the published description
// of the project 8 test (nand2tetris); the recursive fib(4).

load,
output-file FibonacciElement.out,
compare-to FibonacciElement.cmp,
output-list RAM[0]%D1.6.1 RAM[261]%D1.6.1;

set sp 261,

repeat 110 {
  vmstep;
}

output;
