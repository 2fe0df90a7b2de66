//! `Memory` and `Array` (spec sections 3.2, 3.3): the web IDE's first-fit
//! free list, including its bugs (a non-head block's predecessor is not
//! relinked; freed blocks are appended at the tail without merging).

use crate::context::Ctx;
use crate::Stop;

/// Address of the initial free block.
pub(crate) const HEAP_BASE: i32 = 2048;
/// Size of the initial free block (data words after its 2-word header).
pub(crate) const HEAP_SIZE: i32 = 14334;

/// A free-list walk longer than this has revisited a block: every block
/// address is one of 65536 word values or the out-of-range marker.
const MAX_WALK: u32 = 65_537;

impl Ctx<'_> {
    /// `Memory.alloc(n)`: the first free block with size >= n+2 is split; its
    /// header word keeps the stale next pointer. ERR2 for n <= 0, ERR6 when
    /// nothing fits; both return 0.
    pub fn alloc(&mut self, n: i32) -> i32 {
        if n <= 0 {
            self.error(2);
            return 0;
        }
        let mut block = self.os.heap_head;
        for _ in 0..MAX_WALK {
            let next = self.get(block);
            let size = self.get(block + 1);
            if size >= n + 2 {
                self.set(block + 1, n);
                let rest = block + 2 + n;
                self.set(rest, next);
                self.set(rest + 1, size - n - 2);
                if self.os.heap_head == block {
                    self.os.heap_head = rest;
                }
                return block + 2;
            }
            block = next;
            if block == 0 {
                self.error(6);
                return 0;
            }
        }
        self.fatal(Stop::Hang(
            "Memory.alloc walks a free list with a cycle forever (a block was freed twice?)".into(),
        ));
        0
    }

    /// `Memory.deAlloc(p)`: `RAM[p-2] = 0`, then the block is appended after
    /// the first free block whose next is 0. No validation, no merging.
    pub fn dealloc(&mut self, p: i32) {
        let freed = p - 2;
        self.set(freed, 0);
        let mut block = self.os.heap_head;
        for _ in 0..MAX_WALK {
            let next = self.get(block);
            if next == 0 {
                self.set(block, freed);
                return;
            }
            block = next;
        }
        self.fatal(Stop::Hang(
            "Memory.deAlloc walks a free list with a cycle forever (a block was freed twice?)"
                .into(),
        ));
    }

    /// `Array.new(n)`: ERR2 for n <= 0, else `alloc(n)`.
    pub fn array_new(&mut self, n: i32) -> i32 {
        if n <= 0 {
            self.error(2);
            return 0;
        }
        self.alloc(n)
    }
}
