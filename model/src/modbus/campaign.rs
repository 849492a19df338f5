//! The Modbus corruption campaign.
