//! Fallible allocation, the one place the core asks for heap memory.

use alloc::vec::Vec;

use crate::error::Error;

/// An empty vector with room for `len` elements, reserved with
/// `try_reserve_exact`: a refused allocation is [`Error::OutOfMemory`]
/// naming the bytes, never an abort.
pub(crate) fn try_vec<T>(len: usize) -> Result<Vec<T>, Error> {
    let bytes = len
        .checked_mul(core::mem::size_of::<T>())
        .ok_or(Error::SizeOverflow)?;
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| Error::OutOfMemory { bytes })?;
    Ok(v)
}

/// Makes room for `extra` more elements in `v`, growing geometrically but
/// failing with [`Error::OutOfMemory`] instead of aborting.
pub(crate) fn try_grow<T>(v: &mut Vec<T>, extra: usize) -> Result<(), Error> {
    if v.capacity() - v.len() >= extra {
        return Ok(());
    }
    let wanted = v.len().checked_add(extra).ok_or(Error::SizeOverflow)?;
    let target = wanted.max(v.capacity().saturating_mul(2));
    let bytes = target.saturating_mul(core::mem::size_of::<T>());
    v.try_reserve_exact(target - v.len())
        .or_else(|_| v.try_reserve_exact(extra))
        .map_err(|_| Error::OutOfMemory { bytes })
}
