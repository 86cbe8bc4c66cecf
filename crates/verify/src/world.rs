//! A state of the model and its packed form. Unpacked ([`World`]) while a ringlet runs;
//! packed into a few bytes while stored: whose turn it is (one byte), per machine its state
//! (one byte, two when it has over 255), one byte of flags (mode, just entered, started this
//! round) and one of time bits when any of its states has a time test, then the value number
//! of every slot the search stores ([`crate::reduce::Storage`]) and every `saw()` value number
//! as LEB128 varints (values met early, the usual ones, take one byte).

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
    wide_state: Vec<bool>,
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
            wide_state: model
                .machines
                .iter()
                .map(|m| m.states.len() > 255)
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
            if self.wide_state[i] {
                out.extend_from_slice(&c.state.to_le_bytes());
            } else {
                out.push(c.state as u8);
            }
            let status = match c.status {
                Status::Running => 0,
                Status::Suspended => 1,
                Status::Dormant => 2,
            };
            out.push(status | (u8::from(c.just_entered) << 2) | (u8::from(c.fresh) << 3));
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
        let mut machines = Vec::with_capacity(self.wide_state.len());
        for i in 0..self.wide_state.len() {
            let state = if self.wide_state[i] {
                u16::from_le_bytes([next(), next()])
            } else {
                u16::from(next())
            };
            let flags = next();
            let status = match flags & 3 {
                0 => Status::Running,
                1 => Status::Suspended,
                _ => Status::Dormant,
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
                status,
                just_entered: flags & 4 != 0,
                fresh: flags & 8 != 0,
                time,
            });
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
            wide_state: vec![false, true],
            has_time: vec![true, false],
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
