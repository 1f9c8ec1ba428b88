//! A list the plant fills on its ticks, allocated at construction for the
//! most entries it can hold.

use std::ops::{Deref, DerefMut};

/// A `Vec` whose capacity is set once, at construction, for the most
/// entries a tick can put in it (one per segment of the edge), so that no
/// tick allocates. A clone keeps that capacity (a `Vec`'s clone has only
/// its length), so a cloned plant's ticks allocate nothing either.
#[derive(Debug, Default)]
pub(crate) struct TickList<T>(Vec<T>);

impl<T> TickList<T> {
    /// An empty list with room for `capacity` entries.
    pub(crate) fn with_capacity(capacity: usize) -> Self {
        Self(Vec::with_capacity(capacity))
    }
}

impl<T: Clone> Clone for TickList<T> {
    fn clone(&self) -> Self {
        let mut list = Vec::with_capacity(self.0.capacity());
        list.extend_from_slice(&self.0);
        Self(list)
    }
}

impl<T> Deref for TickList<T> {
    type Target = Vec<T>;

    fn deref(&self) -> &Vec<T> {
        &self.0
    }
}

impl<T> DerefMut for TickList<T> {
    fn deref_mut(&mut self) -> &mut Vec<T> {
        &mut self.0
    }
}

#[cfg(test)]
mod tests {
    use super::TickList;

    #[test]
    fn a_clone_keeps_the_capacity() {
        let mut list = TickList::with_capacity(16);
        list.extend([1, 2, 3]);
        let clone = list.clone();
        assert_eq!(*clone, vec![1, 2, 3]);
        assert!(clone.capacity() >= 16, "{}", clone.capacity());
    }
}
