//! The page registers 824 of Schilling & Knittel (section 5): one open row per DRAM bank, the
//! cost of an access in 30 ns slots. Below every unit that reads banks like the TEXRAM's: the
//! chip 802 and its video port, the mipmap generator 816 on its own frame store, the ray
//! caster of Figure 15 and the behavioural chip.

pub mod page_registers_824;
