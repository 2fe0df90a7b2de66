//! `Memory` and `Array` (spec sections 3.2, 3.3): the web IDE's first-fit
//! free list, including its bugs (a non-head block's predecessor is not
//! relinked; freed blocks are appended at the tail without merging); and,
//! under [`Profile::Desktop`], the desktop VM emulator's built-in heap (see
//! [`Ctx::desktop_alloc`]).

use crate::context::Ctx;
use crate::ram::{HEAP_BASE, HEAP_END};
use crate::{Profile, Ram, Stop};

/// The desktop's heap header, as its built-in `Memory.init` writes it: one
/// block at 2048 of capacity 14334 (`RAM[2048]`) whose next block is
/// 16384, the end (`RAM[2049]`).
pub(crate) fn desktop_header(ram: &mut Ram) {
    ram.write(HEAP_BASE, (HEAP_END + 1 - (HEAP_BASE + 2)) as i16);
    ram.write(HEAP_BASE + 1, (HEAP_END + 1) as i16);
}

/// A free-list walk longer than this has revisited a block: every block
/// address is one of 65536 word values or the out-of-range marker.
const MAX_WALK: u32 = 65_537;

impl Ctx<'_> {
    /// `Memory.alloc(n)`: the first free block with size >= n+2 is split; its
    /// header word keeps the stale next pointer. ERR2 for n <= 0, ERR6 when
    /// nothing fits; both return 0.
    pub fn alloc(&mut self, n: i32) -> i32 {
        if self.profile() == Profile::Desktop {
            return self.desktop_alloc(n);
        }
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
        if self.profile() == Profile::Desktop {
            self.desktop_dealloc(p);
            return;
        }
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

    /// Desktop `Memory.alloc(n)`: every block, used or free, is a 2-word
    /// header (capacity, next block) and its data, linked in address order
    /// from 2048; a used block has capacity 0. The first block whose
    /// capacity is at least n is used: if more than n+2 words are left, the
    /// rest becomes a new block after it (linked in between); then its
    /// capacity word is set to 0 and its data address returned. ERR5 for
    /// n < 1, ERR6 when the walk passes the heap's end. Words are 16-bit,
    /// as the desktop's Java `short`s, and every word read or written is
    /// checked (see [`Ctx::checked_get`]).
    pub(crate) fn desktop_alloc(&mut self, n: i32) -> i32 {
        let n = i32::from(n as i16);
        if n < 1 {
            self.error(5);
            return 0;
        }
        let mut block = HEAP_BASE;
        let mut capacity = 0;
        let mut walked = 0u32;
        while block <= HEAP_END {
            capacity = self.checked_get(block);
            if self.halted() {
                return 0;
            }
            if capacity >= n {
                break;
            }
            block = self.checked_get(block + 1);
            walked += 1;
            if walked > MAX_WALK {
                self.fatal(Stop::Hang(
                    "Memory.alloc walks a block list with a cycle forever".into(),
                ));
                return 0;
            }
        }
        if self.halted() {
            return 0;
        }
        if block > HEAP_END {
            self.error(6);
            return 0;
        }
        if capacity > n + 2 {
            self.checked_set(block + n + 2, capacity - n - 2);
            let next = self.checked_get(block + 1);
            self.checked_set(block + n + 3, next);
            self.checked_set(block + 1, block + n + 2);
        }
        self.checked_set(block, 0);
        i32::from((block + 2) as i16)
    }

    /// Desktop `Memory.deAlloc(p)`: the block at p-2 gets back the capacity
    /// up to its next block, and takes that block in too if it is free
    /// (capacity not 0) and in the heap. No other check.
    pub(crate) fn desktop_dealloc(&mut self, p: i32) {
        let block = i32::from((p - 2) as i16);
        let _capacity = self.checked_get(block);
        let next = self.checked_get(block + 1);
        if self.halted() {
            return;
        }
        let next_capacity = if next > HEAP_END {
            0
        } else {
            self.checked_get(next)
        };
        if self.halted() {
            return;
        }
        if next_capacity == 0 {
            self.checked_set(block, next - block - 2);
        } else {
            self.checked_set(block, next - block + next_capacity);
            let after = self.checked_get(next + 1);
            self.checked_set(block + 1, after);
        }
    }
}
