//! The fanuc code table. (Placeholder: filled from the spec digest.)

use super::{AddressInfo, CodeInfo, CodeKind, CodeNum, Param, variants};

pub static ADDRESSES: &[AddressInfo] = &[];

pub static CODES: &[CodeInfo] = &[];

#[allow(dead_code)]
const _USE: (Option<CodeKind>, Option<CodeNum>, Option<Param>, u8) =
    (None, None, None, variants::ALL_SW);
