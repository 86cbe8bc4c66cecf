//! A state of the model and its packed form. Unpacked ([`World`]) while a ringlet runs;
//! packed into a few bytes while stored: whose turn it is (one byte), per machine its state
//! (no byte for a machine of one state, one, or two when it has over 256) and its time bits
//! (one byte, two for a state with over seven time tests) when any of its states has a time
//! test, four bits of flags a machine (mode, just entered, started this round), two machines to
//! a byte, then the value number of every slot the search stores ([`crate::reduce::Storage`])
//! and every `saw()` value number as LEB128 varints (values met early, the usual ones, take one
//! byte).

use crate::model::{Model, SlotId};
use crate::reduce::Storage;
use crate::ringlet::POSTED;
use crate::values::{ValueId, NEVER};

/// A machine's mode, gufsm's `SuspensibleMachine` states.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    Running,
    /// Parked by `suspend`; `resume` enters its state again.
    Suspended,
    /// Not started, or stopped by `Off`: `On` starts it from its initial state.
    Dormant,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct World {
    /// The machine whose turn is next, or the first to consider after it (the runnable one
    /// at or after it, wrapping to a new round).
    pub turn: u8,
    pub machines: Vec<Control>,
    pub values: Vec<ValueId>,
    /// What each `saw(Machine, name)` of the properties read at that machine's last snapshot.
    pub saw: Vec<ValueId>,
}

/// Field widths, fixed per model.
#[derive(Clone, Debug)]
pub struct Layout {
    /// Bytes of each machine's state number: 0, 1 or 2.
    state_bytes: Vec<u8>,
    has_time: Vec<bool>,
    /// The slots a state stores, in slot order.
    stored: Vec<SlotId>,
    /// The free types chosen when read, whose one bit each (posted yet) a state stores.
    chosen: Vec<SlotId>,
    /// Every slot's value in an unpacked world before the stored ones are read: the initial
    /// value of one nothing reads, "never posted" for one chosen when read.
    fill: Vec<ValueId>,
}

impl Layout {
    pub fn new(model: &Model) -> Layout {
        Layout {
            state_bytes: model
                .machines
                .iter()
                .map(|m| match m.states.len() {
                    0 | 1 => 0,
                    2..=256 => 1,
                    _ => 2,
                })
                .collect(),
            has_time: model
                .machines
                .iter()
                .map(|m| m.states.iter().any(|s| !s.time_tests.is_empty()))
                .collect(),
            stored: (0..model.slots.len())
                .filter(|&slot| model.storage[slot] == Storage::Stored)
                .collect(),
            chosen: (0..model.slots.len())
                .filter(|&slot| model.storage[slot] == Storage::ChosenWhenRead)
                .collect(),
            fill: {
                let mut values = model.values.borrow_mut();
                model
                    .slots
                    .iter()
                    .zip(&model.storage)
                    .map(|(slot, storage)| match storage {
                        Storage::Unread => values.intern_option(slot.initial.as_ref()),
                        Storage::Stored | Storage::ChosenWhenRead => NEVER,
                    })
                    .collect()
            },
        }
    }

    pub fn pack(&self, world: &World, out: &mut Vec<u8>) {
        out.push(world.turn);
        for (i, c) in world.machines.iter().enumerate() {
            match self.state_bytes[i] {
                0 => {}
                1 => out.push(c.state as u8),
                _ => out.extend_from_slice(&c.state.to_le_bytes()),
            }
            if self.has_time[i] {
                // Time tests per state are limited to 16 by the model; most states have one.
                if c.time > 0x7f {
                    out.push(0x80 | (c.time & 0x7f) as u8);
                    out.push((c.time >> 7) as u8);
                } else {
                    out.push(c.time as u8);
                }
            }
        }
        for pair in world.machines.chunks(2) {
            let nibble = |c: &Control| {
                let status = match c.status {
                    Status::Running => 0,
                    Status::Suspended => 1,
                    Status::Dormant => 2,
                };
                status | (u8::from(c.just_entered) << 2) | (u8::from(c.fresh) << 3)
            };
            out.push(nibble(&pair[0]) | pair.get(1).map_or(0, |c| nibble(c) << 4));
        }
        for &slot in &self.stored {
            leb128(world.values[slot], out);
        }
        for &v in &world.saw {
            leb128(v, out);
        }
        for byte in self.chosen.chunks(8) {
            let bits = byte
                .iter()
                .enumerate()
                .filter(|(_, &slot)| world.values[slot] == POSTED)
                .fold(0u8, |bits, (i, _)| bits | 1 << i);
            out.push(bits);
        }
    }

    /// Reads a packed world; `saw` gives the count of `saw()` values.
    pub fn unpack(&self, bytes: &[u8], saw: usize) -> World {
        let mut at = 0;
        let mut next = || {
            let b = bytes[at];
            at += 1;
            b
        };
        let turn = next();
        let count = self.state_bytes.len();
        let mut machines = Vec::with_capacity(count);
        for i in 0..count {
            let state = match self.state_bytes[i] {
                0 => 0,
                1 => u16::from(next()),
                _ => u16::from_le_bytes([next(), next()]),
            };
            let time = if self.has_time[i] {
                let low = next();
                if low & 0x80 != 0 {
                    u16::from(low & 0x7f) | (u16::from(next()) << 7)
                } else {
                    u16::from(low)
                }
            } else {
                0
            };
            machines.push(Control {
                state,
                status: Status::Running,
                just_entered: false,
                fresh: false,
                time,
            });
        }
        for pair in machines.chunks_mut(2) {
            let byte = next();
            for (c, flags) in pair.iter_mut().zip([byte & 0xf, byte >> 4]) {
                c.status = match flags & 3 {
                    0 => Status::Running,
                    1 => Status::Suspended,
                    _ => Status::Dormant,
                };
                c.just_entered = flags & 4 != 0;
                c.fresh = flags & 8 != 0;
            }
        }
        let mut rest = &bytes[at..];
        let mut next_number = || {
            let (v, used) = read_leb128(rest);
            rest = &rest[used..];
            v
        };
        let mut values = self.fill.clone();
        for &slot in &self.stored {
            values[slot] = next_number();
        }
        let saw = (0..saw).map(|_| next_number()).collect();
        for (byte, slots) in rest.iter().zip(self.chosen.chunks(8)) {
            for (i, &slot) in slots.iter().enumerate() {
                values[slot] = if byte >> i & 1 == 1 { POSTED } else { NEVER };
            }
        }
        World {
            turn,
            machines,
            values,
            saw,
        }
    }
}

fn leb128(mut v: u32, out: &mut Vec<u8>) {
    while v >= 0x80 {
        out.push((v as u8) | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

fn read_leb128(bytes: &[u8]) -> (u32, usize) {
    let mut v = 0u32;
    for (i, b) in bytes.iter().enumerate() {
        v |= u32::from(b & 0x7f) << (7 * i);
        if b & 0x80 == 0 {
            return (v, i + 1);
        }
    }
    (v, bytes.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_round_trips_at_every_width() {
        let layout = Layout {
            state_bytes: vec![1, 2, 0],
            has_time: vec![true, false, false],
            stored: vec![0, 2],
            chosen: vec![3],
            fill: vec![NEVER, 7, NEVER, NEVER],
        };
        for (time, value) in [(0, 0), (5, 127), (0x7fff, 128), (0x80, u32::MAX)] {
            let world = World {
                turn: 1,
                machines: vec![
                    Control {
                        state: 200,
                        status: Status::Suspended,
                        just_entered: true,
                        fresh: false,
                        time,
                    },
                    Control {
                        state: 300,
                        status: Status::Dormant,
                        just_entered: false,
                        fresh: true,
                        time: 0,
                    },
                    Control {
                        state: 0,
                        status: Status::Running,
                        just_entered: true,
                        fresh: true,
                        time: 0,
                    },
                ],
                values: vec![value, 7, 3, if time > 0 { POSTED } else { NEVER }],
                saw: vec![value],
            };
            let mut bytes = Vec::new();
            layout.pack(&world, &mut bytes);
            assert_eq!(layout.unpack(&bytes, 1), world, "{time} {value}");
        }
    }
}
