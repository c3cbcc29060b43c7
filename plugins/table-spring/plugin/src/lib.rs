//! Exports the `table-spring` law through the Stiction law ABI (`stiction_law_descriptor`).
stiction_law_sdk::export_law!(stiction_law_table_spring::TableSpring);
