//! A state of the model and its packed form. Unpacked ([`SystemState`]) while a ringlet runs;
//! packed while stored into a record of bit fields, each as wide as its values need: whose
//! turn it is, per machine its state number (none for a machine of one state), its time bits
//! (one a time test of its states) and its flags (just entered, started this round, mode, and
//! the bits that order machines' clocks, [`crate::clocks`]: none while they never change),
//! then the value number of every slot the search stores ([`crate::model::Storage`]) and of
//! every `saw()`, then one bit a free type chosen when read (posted yet). A value number wider
//! than its field widens the field; every record of a search has one width.

use crate::model::SlotId;
use crate::model::Storage;
use crate::search::Search;
use crate::values::{ValueId, NEVER};

/// The `turn` of an initial world: machine 0 rings next, and no ringlet has run yet (a free
/// type chosen when read may still be never posted).
pub const FIRST_TURN: u8 = u8::MAX;

/// In the state, a free type chosen when read that the environment has posted (before, it
/// holds [`NEVER`]): what it holds is chosen at each read, but it is never silent again.
pub(crate) const POSTED: ValueId = ValueId::MAX - 1;

/// A machine's mode, gufsm's `SuspensibleMachine` states.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Status {
    Running,
    /// Parked by `suspend`; `resume` enters its state again.
    Suspended,
    /// Not started, or stopped by `Off`: `On` starts it from its initial state.
    Dormant,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Control {
    /// Index into the machine's states.
    pub state: u16,
    pub status: Status,
    /// The state became current and its OnEntry has not run yet.
    pub just_entered: bool,
    /// Started during the current round: its first ringlet is in the next one (§3.1).
    pub fresh: bool,
    /// Which of the current state's time tests are due (bit i: its i-th test).
    pub time: u16,
    /// It arrived in a state whose clocks are ordered during the current round
    /// ([`crate::clocks`]).
    pub arrived: bool,
    /// Bit `r`: its last arrival was no later than that of the machine of clock rank `r`
    /// ([`crate::clocks`]).
    pub order: u8,
    /// Having left its state in the current round: the longest of the tests then due on the
    /// clocks its arrival had started, and the shortest not due, numbered from 1 in the
    /// model's clock durations (0: none; [`crate::clocks::left`]).
    pub left_due: u8,
    pub left_wait: u8,
}

/// The whole model's state, unpacked: whose turn it is, every machine's control, every slot's
/// value and what each `saw()` kept.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct SystemState {
    /// The machine whose turn is next, or the first to consider after it (the runnable one
    /// at or after it, wrapping to a new round).
    pub turn: u8,
    pub machines: Vec<Control>,
    pub values: Vec<ValueId>,
    /// What each `saw(Machine, name)` of the properties read at that machine's last snapshot.
    pub saw: Vec<ValueId>,
}

/// The lowest `bits` bits set (all of them from 128 on).
fn low_bits(bits: u32) -> u128 {
    u128::MAX.checked_shr(128 - bits.min(128)).unwrap_or(0)
}

/// Field widths in bits. A machine's state number and time bits are as wide as the model says
/// they can need; its flags start with no bits and value numbers as wide as the values the
/// text names, and each is as wide as what the search has met needed: a value that does not
/// fit makes [`Layout::pack`] say which field must widen.
#[derive(Clone, Debug)]
pub struct Layout {
    /// Per field, in packing order: turn; per machine its state, time bits and flags;
    /// every stored slot's value number; every `saw()` value number; a bit per chosen slot.
    widths: Vec<u8>,
    /// The sum of the widths.
    bits: usize,
    machines: usize,
    /// The slots a state stores, in slot order.
    stored: Vec<SlotId>,
    /// The free types chosen when read, whose one bit each (posted yet) a state stores.
    chosen: Vec<SlotId>,
    /// Every slot's value in an unpacked world before the stored ones are read: the initial
    /// value of one nothing reads, "never posted" for one chosen when read.
    fill: Vec<ValueId>,
    saw: usize,
}

/// A value that does not fit its field: the field's index and the bits it needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TooNarrow {
    pub field: usize,
    pub bits: u8,
}

/// Bits that hold every number up to `max` (both engines' fields are this wide).
pub(crate) fn bits_for(max: u64) -> u8 {
    (u64::BITS - max.leading_zeros()) as u8
}

impl Layout {
    pub fn new(model: &Search) -> Layout {
        let stored: Vec<SlotId> = (0..model.slots.len())
            .filter(|&slot| model.storage[slot] == Storage::Stored)
            .collect();
        let chosen: Vec<SlotId> = (0..model.slots.len())
            .filter(|&slot| model.storage[slot] == Storage::ChosenWhenRead)
            .collect();
        let mut values = model.values.borrow_mut();
        let fill = model
            .slots
            .iter()
            .zip(&model.storage)
            .map(|(slot, storage)| match storage {
                Storage::Unread => values.intern_option(slot.initial.as_ref()),
                Storage::Stored | Storage::ChosenWhenRead => NEVER,
            })
            .collect();
        let mut widths = vec![bits_for(model.machines.len() as u64 + 1)];
        for m in &model.machines {
            widths.push(bits_for(m.states.len().saturating_sub(1) as u64));
            widths.push(m.most_time_tests() as u8);
            // Most machines only ever run, so their flags start with no bits at all.
            widths.push(0);
        }
        // Value numbers start as wide as the values the text names (numbered as the model was
        // built), so a search widens them only for values its steps make.
        let named = bits_for(values.len() as u64);
        widths.extend(std::iter::repeat_n(named, stored.len() + model.saw.len()));
        widths.extend(std::iter::repeat_n(1, chosen.len()));
        Layout {
            bits: widths.iter().map(|&w| usize::from(w)).sum(),
            widths,
            machines: model.machines.len(),
            stored,
            chosen,
            fill,
            saw: model.saw.len(),
        }
    }

    /// The bytes every packed state takes.
    pub fn bytes(&self) -> usize {
        self.widths
            .iter()
            .map(|&w| usize::from(w))
            .sum::<usize>()
            .div_ceil(8)
    }

    /// This layout with `field` widened to at least `bits`. Value numbers are shared by every
    /// slot, so a number one slot met the others may meet next: every value field widens with
    /// it, and a search packs its records again once rather than once a slot.
    pub fn widened(&self, narrow: TooNarrow) -> Layout {
        let mut wider = self.clone();
        let values = 1 + 3 * self.machines..1 + 3 * self.machines + self.stored.len() + self.saw;
        let fields = if values.contains(&narrow.field) {
            values
        } else {
            narrow.field..narrow.field + 1
        };
        for w in &mut wider.widths[fields] {
            *w = (*w).max(narrow.bits);
        }
        wider.bits = wider.widths.iter().map(|&w| usize::from(w)).sum();
        wider
    }

    /// Whether a record fits in a `u128`, on which the explicit search's step memo works.
    pub fn fits_register(&self) -> bool {
        self.bits <= 128
    }

    /// The bit a field starts at, in a record read as a little-endian number.
    fn field_start(&self, field: usize) -> u32 {
        self.widths[..field].iter().map(|&w| u32::from(w)).sum()
    }

    /// The bits of `field` in a record read as a little-endian `u128`; none for a field
    /// that ends past its 128 bits (a layout widened past a register, whose masks the memos
    /// make anew but no longer use).
    fn field_mask(&self, field: usize) -> u128 {
        let start = self.field_start(field);
        match self.widths.get(field).map(|&w| u32::from(w)) {
            Some(w) if start + w <= 128 => low_bits(w).checked_shl(start).unwrap_or(0),
            _ => 0,
        }
    }

    /// The bits of whose turn it is.
    pub fn turn_mask(&self) -> u128 {
        self.field_mask(0)
    }

    /// The bits of machine `k`'s control: its state, time bits and flags.
    pub fn control_mask(&self, k: usize) -> u128 {
        (1..4).fold(0, |m, f| m | self.field_mask(f + 3 * k))
    }

    /// The bit of machine `k`'s "started this round" flag, when its flags field has one.
    pub fn fresh_mask(&self, k: usize) -> u128 {
        let field = 3 + 3 * k;
        if self.widths[field] >= 2 {
            // None past a register's bits, as for every mask here.
            1u128.checked_shl(self.field_start(field) + 1).unwrap_or(0)
        } else {
            0
        }
    }

    /// The bits of machine `k`'s flags a new round clears besides "started this round":
    /// [`Control::arrived`], [`Control::left_due`] and [`Control::left_wait`], those its flags
    /// field has.
    pub fn round_mask(&self, k: usize) -> u128 {
        let field = 3 + 3 * k;
        let cleared: u128 = 1 << 4 | 0xffff << 13;
        let mine = cleared & low_bits(u32::from(self.widths[field]));
        mine.checked_shl(self.field_start(field)).unwrap_or(0)
    }

    /// The bits a record keeps of `slot`: its value number when stored, its one bit when
    /// chosen when read, none when unread.
    pub fn slot_mask(&self, slot: SlotId) -> u128 {
        let values = 1 + 3 * self.machines;
        if let Ok(i) = self.stored.binary_search(&slot) {
            return self.field_mask(values + i);
        }
        if let Ok(i) = self.chosen.binary_search(&slot) {
            return self.field_mask(values + self.stored.len() + self.saw + i);
        }
        0
    }

    /// The bits of the value `saw()` number `j` keeps.
    pub fn saw_mask(&self, j: usize) -> u128 {
        self.field_mask(1 + 3 * self.machines + self.stored.len() + j)
    }

    /// Where machine `k`'s state number lies in a record read as a `u128`: its first bit and
    /// the mask of its width.
    pub fn state_field(&self, k: usize) -> (u32, u128) {
        let field = 1 + 3 * k;
        let width = self.widths[field];
        (self.field_start(field), (1u128 << width) - 1)
    }

    /// [`Layout::pack`] into a `u128`, for a layout that [`Layout::fits_register`].
    pub fn pack_register(&self, world: &SystemState) -> Result<u128, TooNarrow> {
        let mut bits = Register { acc: 0, used: 0 };
        self.pack_into(world, &mut bits)?;
        Ok(bits.acc)
    }

    /// Packs `world` into [`Layout::bytes`] bytes appended to `out`, or says which field is too
    /// narrow for it (`out` then holds a part of the record).
    pub fn pack(&self, world: &SystemState, out: &mut Vec<u8>) -> Result<(), TooNarrow> {
        // Most records fit in a register, which is filled before a byte is written.
        if self.bits <= 128 {
            let mut bits = Register { acc: 0, used: 0 };
            self.pack_into(world, &mut bits)?;
            let mut acc = bits.acc;
            for _ in 0..self.bytes() {
                out.push(acc as u8);
                acc >>= 8;
            }
            return Ok(());
        }
        let mut bits = BitWriter {
            out,
            acc: 0,
            used: 0,
        };
        self.pack_into(world, &mut bits)?;
        bits.finish();
        Ok(())
    }

    fn pack_into(&self, world: &SystemState, bits: &mut impl FieldWriter) -> Result<(), TooNarrow> {
        let mut field = 0;
        let mut put = |v: u64| {
            let width = self.widths[field];
            if v >> width != 0 {
                return Err(TooNarrow {
                    field,
                    bits: bits_for(v),
                });
            }
            bits.put(v, width);
            field += 1;
            Ok(())
        };
        // The first turn (no ringlet yet) is numbered 0, machine k's k + 1.
        put(u64::from(world.turn.wrapping_add(1)))?;
        for c in &world.machines {
            put(u64::from(c.state))?;
            put(u64::from(c.time))?;
            let status = match c.status {
                Status::Running => 0,
                Status::Suspended => 1,
                Status::Dormant => 2,
            };
            // The flags that change most often in the low bits, so a field stays narrow.
            put(u64::from(c.just_entered)
                | u64::from(c.fresh) << 1
                | status << 2
                | u64::from(c.arrived) << 4
                | u64::from(c.order) << 5
                | u64::from(c.left_due) << 13
                | u64::from(c.left_wait) << 21)?;
        }
        for &slot in &self.stored {
            put(u64::from(world.values[slot]))?;
        }
        for &v in &world.saw {
            put(u64::from(v))?;
        }
        for &slot in &self.chosen {
            put(u64::from(world.values[slot] == POSTED))?;
        }
        Ok(())
    }

    /// Reads a world [`Layout::pack`] packed with this layout.
    pub fn unpack(&self, bytes: &[u8]) -> SystemState {
        let mut world = SystemState {
            turn: 0,
            machines: Vec::with_capacity(self.machines),
            values: Vec::with_capacity(self.fill.len()),
            saw: Vec::with_capacity(self.saw),
        };
        self.unpack_into(bytes, &mut world);
        world
    }

    /// Reads a world [`Layout::pack_register`] packed with this layout.
    pub fn unpack_record(&self, record: u128) -> SystemState {
        self.unpack(&record.to_le_bytes()[..self.bytes()])
    }

    /// [`Layout::unpack`] into a world already allocated, which a search reuses state after
    /// state.
    pub fn unpack_into(&self, bytes: &[u8], world: &mut SystemState) {
        if self.bits <= 128 {
            let acc = bytes
                .iter()
                .rev()
                .fold(0u128, |acc, &b| acc << 8 | u128::from(b));
            self.unpack_from(&mut Register { acc, used: 0 }, world);
        } else {
            let mut bits = BitReader {
                bytes,
                at: 0,
                acc: 0,
                held: 0,
            };
            self.unpack_from(&mut bits, world);
        }
    }

    fn unpack_from(&self, bits: &mut impl FieldReader, world: &mut SystemState) {
        let mut widths = self.widths.iter();
        let mut next = || bits.take(widths.next().copied().unwrap_or(0));
        world.turn = (next() as u8).wrapping_sub(1);
        world.machines.clear();
        for _ in 0..self.machines {
            let state = next() as u16;
            let time = next() as u16;
            let flags = next();
            world.machines.push(Control {
                state,
                status: match flags >> 2 & 3 {
                    0 => Status::Running,
                    1 => Status::Suspended,
                    _ => Status::Dormant,
                },
                just_entered: flags & 1 != 0,
                fresh: flags & 2 != 0,
                time,
                arrived: flags & 16 != 0,
                order: (flags >> 5) as u8,
                left_due: (flags >> 13) as u8,
                left_wait: (flags >> 21) as u8,
            });
        }
        world.values.clear();
        world.values.extend_from_slice(&self.fill);
        for &slot in &self.stored {
            world.values[slot] = next() as ValueId;
        }
        world.saw.clear();
        for _ in 0..self.saw {
            world.saw.push(next() as ValueId);
        }
        for &slot in &self.chosen {
            world.values[slot] = if next() == 1 { POSTED } else { NEVER };
        }
    }
}

/// Where fields of at most 32 bits are written.
trait FieldWriter {
    fn put(&mut self, v: u64, width: u8);
}

/// Where fields are read from.
trait FieldReader {
    fn take(&mut self, width: u8) -> u64;
}

/// A record of at most 128 bits held whole: written from its low bits up, read by shifting
/// them out.
struct Register {
    acc: u128,
    used: u32,
}

impl FieldWriter for Register {
    fn put(&mut self, v: u64, width: u8) {
        self.acc |= u128::from(v) << self.used;
        self.used += u32::from(width);
    }
}

impl FieldReader for Register {
    fn take(&mut self, width: u8) -> u64 {
        let v = (self.acc as u64) & ((1u64 << width) - 1);
        self.acc >>= width;
        v
    }
}

/// Appends numbers of at most 32 bits to a byte vector, least significant bit first, four
/// bytes at a time.
struct BitWriter<'a> {
    out: &'a mut Vec<u8>,
    acc: u64,
    used: u32,
}

impl FieldWriter for BitWriter<'_> {
    fn put(&mut self, v: u64, width: u8) {
        self.acc |= v << self.used;
        self.used += u32::from(width);
        if self.used >= 32 {
            self.out.extend_from_slice(&(self.acc as u32).to_le_bytes());
            self.acc >>= 32;
            self.used -= 32;
        }
    }
}

impl BitWriter<'_> {
    fn finish(mut self) {
        // A byte at a time: a copy of a length unknown here is a call.
        while self.used > 0 {
            self.out.push(self.acc as u8);
            self.acc >>= 8;
            self.used = self.used.saturating_sub(8);
        }
    }
}

/// Reads what a [`BitWriter`] wrote; past the end it reads zeros.
struct BitReader<'a> {
    bytes: &'a [u8],
    at: usize,
    acc: u64,
    held: u32,
}

impl FieldReader for BitReader<'_> {
    fn take(&mut self, width: u8) -> u64 {
        let width = u32::from(width);
        if self.held < width {
            let word = match self.bytes.get(self.at..self.at + 4) {
                Some(&[a, b, c, d]) => u32::from_le_bytes([a, b, c, d]),
                _ => {
                    let mut word = [0u8; 4];
                    let rest = self.bytes.get(self.at..).unwrap_or(&[]);
                    word[..rest.len()].copy_from_slice(rest);
                    u32::from_le_bytes(word)
                }
            };
            self.at += 4;
            self.acc |= u64::from(word) << self.held;
            self.held += 32;
        }
        let v = self.acc & ((1u64 << width) - 1);
        self.acc >>= width;
        self.held -= width;
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout() -> Layout {
        Layout {
            // turn; three machines (state, time, flags); two stored slots; one saw; one chosen.
            widths: vec![2, 8, 2, 4, 9, 0, 4, 0, 0, 4, 3, 3, 3, 1],
            bits: 43,
            machines: 3,
            stored: vec![0, 2],
            chosen: vec![3],
            fill: vec![NEVER, 7, NEVER, NEVER],
            saw: 1,
        }
    }

    fn world(time: u16, value: ValueId) -> SystemState {
        SystemState {
            turn: 1,
            machines: vec![
                Control {
                    state: 200,
                    status: Status::Suspended,
                    just_entered: true,
                    fresh: false,
                    time,
                    arrived: false,
                    order: 0,
                    left_due: 0,
                    left_wait: 0,
                },
                Control {
                    state: 300,
                    status: Status::Dormant,
                    just_entered: false,
                    fresh: true,
                    time: 0,
                    arrived: false,
                    order: 0,
                    left_due: 0,
                    left_wait: 0,
                },
                Control {
                    state: 0,
                    status: Status::Running,
                    just_entered: true,
                    fresh: true,
                    time: 0,
                    arrived: false,
                    order: 0,
                    left_due: 0,
                    left_wait: 0,
                },
            ],
            values: vec![value, 7, 3, if time > 0 { POSTED } else { NEVER }],
            saw: vec![value],
        }
    }

    #[test]
    fn a_layout_widened_past_a_register_has_masks_only_inside_its_bits() {
        let mut layout = layout();
        // Three slots of 32 bits and a bit: 130 bits in all, the last two fields past 128.
        for field in 10..13 {
            layout = layout.widened(TooNarrow { field, bits: 32 });
        }
        assert!(!layout.fits_register());
        assert_eq!(layout.field_mask(0), 0b11);
        assert_eq!(layout.slot_mask(0), u128::from(u32::MAX) << 33);
        assert_eq!(layout.saw_mask(0), 0, "bits 97 to 129 pass the register");
        assert_eq!(layout.slot_mask(3), 0, "bit 129 passes the register");
        // Every mask of every machine is made, none overflowing a shift.
        for k in 0..3 {
            let _ = (
                layout.control_mask(k),
                layout.fresh_mask(k),
                layout.round_mask(k),
            );
        }
        assert_eq!(low_bits(0), 0);
        assert_eq!(low_bits(128), u128::MAX);
    }

    #[test]
    fn packing_round_trips_and_widens_what_does_not_fit() {
        let mut layout = layout();
        for (time, value) in [(0, 0), (3, 5), (1, 128), (2, u32::MAX)] {
            let w = world(time, value);
            let mut bytes = Vec::new();
            while let Err(narrow) = layout.pack(&w, &mut bytes) {
                assert!(narrow.bits > layout.widths[narrow.field], "{narrow:?}");
                layout = layout.widened(narrow);
                bytes.clear();
            }
            assert_eq!(bytes.len(), layout.bytes());
            assert_eq!(layout.unpack(&bytes), w, "{time} {value}");
        }
        assert_eq!(
            layout.widths[10], 32,
            "the stored slot grew to the widest value"
        );
        assert_eq!(
            layout.widths[10..14],
            [32, 32, 32, 1],
            "every value field grew with it, the chosen bit did not"
        );
        let mut first = world(0, 0);
        first.turn = crate::world::FIRST_TURN;
        let mut bytes = Vec::new();
        layout
            .pack(&first, &mut bytes)
            .expect("the first turn fits");
        assert_eq!(layout.unpack(&bytes), first);
    }

    #[test]
    fn records_wider_than_a_register_round_trip_too() {
        let layout = Layout {
            widths: vec![1, 32, 32, 32, 32, 32, 3],
            bits: 164,
            machines: 0,
            stored: (0..6).collect(),
            chosen: Vec::new(),
            fill: vec![NEVER; 6],
            saw: 0,
        };
        let world = SystemState {
            turn: crate::world::FIRST_TURN,
            machines: Vec::new(),
            values: vec![u32::MAX, 1, 1 << 31, 3, 4, 5],
            saw: Vec::new(),
        };
        let mut bytes = Vec::new();
        layout.pack(&world, &mut bytes).expect("every value fits");
        assert_eq!(bytes.len(), 21);
        assert_eq!(layout.unpack(&bytes), world);
    }
}
