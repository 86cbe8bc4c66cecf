//! Values as the packed state holds them: every value a run can produce is interned once and a
//! state stores its number (0 for "never posted"), so a state is a few bytes however long the
//! texts or lists it speaks of.

use proclaim_board::Value;
use rustc_hash::FxHashMap;

/// The number of a value in [`Values`]; [`NEVER`] is "never posted" (no value at all).
pub type ValueId = u32;

/// A whiteboard type nobody has posted yet, or an extern before its first assignment.
pub const NEVER: ValueId = 0;

/// `Value` holds an `f64`, so it is neither `Eq` nor `Hash`; this is its exact, hashable twin
/// (a float by its bits: `0.0` and `-0.0` are different values, as they print differently).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Key {
    Bool(bool),
    Int(i64),
    Float(u64),
    Str(String),
    Bytes(Vec<u8>),
    List(Vec<Key>),
}

pub(crate) fn key(value: &Value) -> Key {
    match value {
        Value::Bool(b) => Key::Bool(*b),
        Value::Int(i) => Key::Int(*i),
        Value::Float(x) => Key::Float(x.to_bits()),
        Value::Str(s) => Key::Str(s.clone()),
        Value::Bytes(b) => Key::Bytes(b.clone()),
        Value::List(l) => Key::List(l.iter().map(key).collect()),
    }
}

/// Every value met so far, numbered from 1 in order of first meeting.
#[derive(Debug, Default)]
pub struct Values {
    all: Vec<Value>,
    ids: FxHashMap<Key, ValueId>,
    /// Bytes the texts, byte strings and lists hold outside the two tables (twice: the value
    /// and its key).
    heap: usize,
}

/// The bytes a value holds outside itself.
fn heap_bytes(value: &Value) -> usize {
    match value {
        Value::Str(s) => s.len(),
        Value::Bytes(b) => b.len(),
        Value::List(l) => l
            .iter()
            .map(|v| std::mem::size_of::<Value>() + heap_bytes(v))
            .sum(),
        _ => 0,
    }
}

impl Values {
    /// The number of `value`, giving it one when it is new.
    pub fn intern(&mut self, value: &Value) -> ValueId {
        let k = key(value);
        if let Some(&id) = self.ids.get(&k) {
            return id;
        }
        self.heap += 2 * heap_bytes(value);
        self.all.push(value.clone());
        let id = self.all.len() as ValueId;
        self.ids.insert(k, id);
        id
    }

    /// The number of `value` when it was met, without numbering it.
    pub fn find(&self, value: &Value) -> Option<ValueId> {
        self.ids.get(&key(value)).copied()
    }

    /// An optional value's number: [`NEVER`] for none.
    pub fn intern_option(&mut self, value: Option<&Value>) -> ValueId {
        value.map_or(NEVER, |v| self.intern(v))
    }

    /// The value numbered `id`; `None` for [`NEVER`].
    pub fn get(&self, id: ValueId) -> Option<&Value> {
        id.checked_sub(1).map(|i| &self.all[i as usize])
    }

    /// How many distinct values were met (the counters a model's exploration grew).
    pub fn len(&self) -> usize {
        self.all.len()
    }

    pub fn is_empty(&self) -> bool {
        self.all.is_empty()
    }

    /// The bytes the values hold (part of what `--max-memory` bounds: a counter's values grow
    /// with the states), and at most what one more would add when the tables must grow.
    pub fn bytes(&self) -> usize {
        let entry = std::mem::size_of::<(Key, ValueId)>() + 1;
        self.all.capacity() * std::mem::size_of::<Value>() + self.ids.capacity() * entry + self.heap
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_values_share_a_number_and_never_is_zero() {
        let mut values = Values::default();
        let a = values.intern(&Value::Str("on".into()));
        let b = values.intern(&Value::Int(1));
        assert_eq!(values.intern(&Value::Str("on".into())), a);
        assert_ne!(a, b);
        assert_ne!(values.intern(&Value::Float(1.0)), b, "1.0 is no int");
        assert_eq!(values.intern_option(None), NEVER);
        assert_eq!(values.get(NEVER), None);
        assert_eq!(values.get(b), Some(&Value::Int(1)));
    }

    #[test]
    fn the_bytes_grow_with_the_values_and_their_texts() {
        let mut values = Values::default();
        let empty = values.bytes();
        values.intern(&Value::Int(1));
        let one = values.bytes();
        assert!(one > empty);
        for i in 2..1000 {
            values.intern(&Value::Int(i));
        }
        assert!(values.bytes() >= 999 * std::mem::size_of::<Value>());
        let before = values.bytes();
        values.intern(&Value::Str("x".repeat(10_000)));
        assert!(values.bytes() >= before + 20_000);
    }
}
