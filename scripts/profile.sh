#!/usr/bin/env bash
# Where the host time of one benchmark-corpus program goes on the compiled
# engine: by VM function, and by VM instruction kind.
#   scripts/profile.sh PROGRAM    (a corpus name: getters, recursion, jack-port, ...)
# Runs `engine_cpu corpus PROGRAM native` (about a CPU second of runs, the
# program compiled once beforehand) under `perf record`, with the compiled
# code's map (HACK_VM_CODE_MAP: which VM instruction each stretch of host
# code runs for), and joins perf's samples to it. Each compiled-code sample
# counts for the instruction it lies in, split by part: the instruction
# itself, its block's entry tests, the function's entry, the leave path,
# and the code that no instruction owns (the prologue, and the register
# allocator's moves at the start of a block). Other samples
# go by where they are: OS built-ins, the host call of a built-in,
# the interpreter and dispatcher, compiling, the rest. Needs Linux perf.
set -euo pipefail
cd "$(dirname "$0")/.."

name=${1:?usage: scripts/profile.sh PROGRAM}
if ! command -v perf >/dev/null; then
    echo "profile.sh needs Linux perf (the linux-tools package)" >&2
    exit 2
fi
cargo build --quiet --release -p hack-vm --example engine_cpu
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
HACK_VM_CODE_MAP=$tmp/map.tsv perf record --quiet -o "$tmp/perf.data" \
    target/release/examples/engine_cpu corpus "$name" native
perf script -i "$tmp/perf.data" -F ip,sym,symoff 2>/dev/null >"$tmp/samples"

perl -e '
    my ($map, $samples) = @ARGV;
    my %ranges;    # function => [[start, end, kind, part], ...]
    open(my $m, "<", $map) or die "no code map: $!";
    while (<$m>) {
        chomp;
        my ($f, $s, $e, $pc, $part, $kind) = split /\t/;
        push @{$ranges{$f}}, [$s, $e, $kind, $part];
    }
    my (%by_fn, %by_kind, %by_part, $total, $compiled);
    open(my $in, "<", $samples) or die;
    while (<$in>) {
        s/^\s*[0-9a-f]+\s*//; s/\s+$//;
        next if $_ eq "";
        $total++;
        my ($sym, $off) = /^(.*)\+0x([0-9a-f]+)$/ ? ($1, hex $2) : ($_, 0);
        if (my $r = $ranges{$sym}) {
            $compiled++;
            $by_fn{$sym}++;
            # Host code no instruction owns: the prologue, and the moves,
            # spills and reloads the register allocator puts at block starts
            # (those inside a block go with the instruction before them, and
            # the epilogue with the return or leave it ends).
            my ($kind, $part) = ("(prologue, block-start moves)", "prologue, block-start moves");
            for my $x (@$r) {
                if ($off >= $x->[0] && $off < $x->[1]) {
                    $part = $x->[3];
                    $kind = $part eq "op" ? $x->[2] : "($part)";
                    last;
                }
            }
            $by_kind{$kind}++;
            $by_part{$part}++;
            next;
        }
        my $where = $sym =~ /^jack_os::/ ? "OS built-ins"
            : $sym =~ /^hack_vm::native::builtin/ ? "host call of a built-in"
            : $sym =~ /^hack_vm::/ ? "interpreter, dispatcher"
            : $sym =~ /cranelift|regalloc/ ? "compiling"
            : "other (loading, allocator, kernel)";
        $by_fn{"[$where]"}++;
    }
    die "no samples\n" unless $total;
    my $table = sub {
        my ($title, $h, $of) = @_;
        printf "\n| %s | share |\n|---|---:|\n", $title;
        for my $k (sort { $h->{$b} <=> $h->{$a} } keys %$h) {
            my $p = 100 * $h->{$k} / $of;
            printf "| %s | %.1f%% |\n", $k, $p if $p >= 0.5;
        }
    };
    printf "%d samples, %.1f%% in compiled code\n", $total, 100 * $compiled / $total;
    $table->("where (all samples)", \%by_fn, $total);
    if ($compiled) {
        $table->("VM instruction kind (compiled code)", \%by_kind, $compiled);
        $table->("part (compiled code)", \%by_part, $compiled);
    }
' "$tmp/map.tsv" "$tmp/samples"
